// vesica-replay --png-dir writes every picture of the committed dissection under Xvfb (Mesa's
// software renderer). It used to segfault in VTK's translucent pass at its 11th picture: each
// picture made and destroyed its own render window, and the membrane and smoke were drawn from
// buffers of a context already gone. The test runs the real program, as a user would.

#include <gtest/gtest.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPNGReader.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

namespace {

namespace fs = std::filesystem;

// The recording's last time stamp (its last line's first field).
double RecordingDuration(const fs::path& csv) {
  std::ifstream in(csv);
  std::string line, last;
  while (std::getline(in, line))
    if (!line.empty() && line[0] != '#') last = line;
  return std::stod(last.substr(0, last.find(',')));
}

TEST(ReplayPngs, EveryPictureOfTheCommittedDissectionIsWritten) {
  const fs::path recording = fs::path(VESICA_SOURCE_DIR) / "data/recordings/dissection.csv";
  const fs::path dir = fs::temp_directory_path() / ("vesica_field_replay_png_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  const std::string command = std::string(VESICA_REPLAY_EXE) + " " + recording.string() + " --png-dir " +
                              dir.string() + " --png-every-s 0.5 --width 320 --height 180 > " +
                              (dir.string() + ".log") + " 2>&1";
  const int status = std::system(command.c_str());
  ASSERT_TRUE(WIFEXITED(status)) << "vesica-replay died (signal " << (WIFSIGNALED(status) ? WTERMSIG(status) : 0)
                                 << "); log " << dir << ".log";
  ASSERT_EQ(WEXITSTATUS(status), 0) << "log " << dir << ".log";

  // One picture at t = 0, 0.5, 1.0, ... while the recording lasts.
  const double duration_s = RecordingDuration(recording);
  const int expected = static_cast<int>(std::floor(duration_s / 0.5 + 1e-9)) + 1;
  int count = 0;
  for (const auto& entry : fs::directory_iterator(dir)) {
    ++count;
    vtkNew<vtkPNGReader> reader;
    ASSERT_TRUE(reader->CanReadFile(entry.path().string().c_str())) << entry.path();
    reader->SetFileName(entry.path().string().c_str());
    reader->Update();
    int dims[3];
    reader->GetOutput()->GetDimensions(dims);
    EXPECT_EQ(dims[0], 320) << entry.path();
    EXPECT_EQ(dims[1], 180) << entry.path();
  }
  EXPECT_NEAR(count, expected, 1) << "pictures in " << dir;
  fs::remove_all(dir);
  fs::remove(dir.string() + ".log");
}

}  // namespace
