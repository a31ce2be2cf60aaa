// vesica-register end to end (issue 35): a registered series ParaView can open, the displacement
// field and residuals, the warped CT slice; bad input refused naming the file and line, with
// nothing written.

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "app/mesh_io/mesh_io.h"
#include "app/patient/patient_files.h"
#include "app/register/control_point_csv.h"
#include "app/register/displacement_csv.h"
#include "physics/mesh/primitives.h"
#include "tests/registration/registration_liver.h"

namespace vesica {
namespace {

namespace fs = std::filesystem;

struct ToolRun {
  int exit_code = 0;
  std::string output;
};

ToolRun RunTool(const std::string& arguments) {
  const fs::path log = fs::temp_directory_path() / "vesica_register_test.log";
  const std::string command = std::string(VESICA_REGISTER) + " " + arguments + " > " + log.string() + " 2>&1";
  ToolRun run;
  const int status = std::system(command.c_str());
  run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream in(log);
  std::stringstream text;
  text << in.rdbuf();
  run.output = text.str();
  return run;
}

int CountLines(const fs::path& file) {
  std::ifstream in(file);
  int lines = 0;
  for (std::string line; std::getline(in, line);) ++lines;
  return lines;
}

class VesicaRegisterTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("vesica_register_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    mesh_ = physics::MakeBoxTetMesh(Eigen::Vector3d(0.12, 0.08, 0.06), Eigen::Vector3i(6, 4, 3));
    app::WriteTetrahedralMesh(mesh_, dir_ / "box.vtu");
    // Three frames: the box moved 0, 2 and 4 mm along z, its outline tracked on two planes.
    std::ofstream csv(dir_ / "points.csv");
    csv << "# three frames of a box moving cranially\n"
        << "frame,time_s,x_m,y_m,z_m,nx,ny,nz,confidence,plane\n";
    csv.precision(10);
    for (int frame = 0; frame < 3; ++frame) {
      physics::Vertices x = mesh_.vertices;
      x.col(2).array() += 0.002 * frame;
      auto points = test::SampleContour(mesh_, x, 1, 0.04, 8, 0, 0.0, 1);
      auto sagittal = test::SampleContour(mesh_, x, 0, 0.06, 6, 1, 0.0, 1);
      points.insert(points.end(), sagittal.begin(), sagittal.end());
      for (const auto& p : points)
        csv << frame << ',' << 0.4175 * frame << ',' << p.p_W.x() << ',' << p.p_W.y() << ',' << p.p_W.z() << ','
            << p.inward_normal_W.x() << ',' << p.inward_normal_W.y() << ',' << p.inward_normal_W.z() << ",1," << p.plane
            << '\n';
    }
  }
  void TearDown() override { fs::remove_all(dir_); }

  // points.csv with `line` (1-based) replaced.
  fs::path WithLine(int line, const std::string& text) {
    std::ifstream in(dir_ / "points.csv");
    const fs::path out = dir_ / "bad.csv";
    std::ofstream bad(out);
    int n = 0;
    for (std::string l; std::getline(in, l);) bad << (++n == line ? text : l) << '\n';
    return out;
  }
  void ExpectRefused(const std::string& arguments, const std::string& message) {
    const ToolRun run = RunTool(arguments + " --out " + (dir_ / "out").string());
    EXPECT_EQ(run.exit_code, 1) << run.output;
    EXPECT_NE(run.output.find(message), std::string::npos) << run.output;
    EXPECT_FALSE(fs::exists(dir_ / "out")) << "something was written for: " << message;
  }

  fs::path dir_;
  physics::TetrahedralMesh mesh_;
};

TEST_F(VesicaRegisterTest, WritesTheSeriesTheFieldAndTheResiduals) {
  const fs::path out = dir_ / "out";
  const ToolRun run = RunTool((dir_ / "box.vtu").string() + " " + (dir_ / "points.csv").string() + " --out " +
                              out.string() + " --steps-per-frame 6");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_NE(run.output.find("3/3 frames"), std::string::npos) << run.output;  // the progress bar
  for (const char* f : {"registered.pvd", "registered_0000.vtu", "registered_0001.vtu", "registered_0002.vtu"})
    EXPECT_TRUE(fs::exists(out / f)) << f;
  EXPECT_EQ(CountLines(out / "displacement.csv"), 1 + 3 * mesh_.num_vertices());
  EXPECT_EQ(CountLines(out / "residuals.csv"), 1 + 3);
  // The last frame's mesh is the box moved 4 mm up (read back through VTK).
  const physics::TetrahedralMesh last = app::ReadTetrahedralMesh(out / "registered_0002.vtu");
  const double mean_dz = (last.vertices.col(2) - mesh_.vertices.col(2)).mean();
  EXPECT_NEAR(mean_dz, 0.004, 0.0005);
  std::ifstream pvd(out / "registered.pvd");
  std::stringstream text;
  text << pvd.rdbuf();
  EXPECT_NE(text.str().find("file=\"registered_0002.vtu\""), std::string::npos);

  // displacement.csv read back as a series replays the registered frames (the patient's source).
  const physics::DisplacementSeries series = app::registration::ReadDisplacementSeries(out / "displacement.csv", mesh_);
  const auto bound = series.Bind({mesh_.vertices.row(0).transpose()});  // node 0 at rest
  const Eigen::Vector3d node0 = (last.vertices.row(0) - mesh_.vertices.row(0)).transpose();
  EXPECT_TRUE(series.Sample(bound, 2 * 0.4175)[0].isApprox(node0, 1e-6));
  EXPECT_THROW(app::registration::ReadDisplacementSeries(out / "residuals.csv", mesh_),
               app::registration::RegisterInputError);

  // --frames picks a range.
  const ToolRun some = RunTool((dir_ / "box.vtu").string() + " " + (dir_ / "points.csv").string() + " --out " +
                               (dir_ / "some").string() + " --frames 1:2");
  ASSERT_EQ(some.exit_code, 0) << some.output;
  EXPECT_FALSE(fs::exists(dir_ / "some" / "registered_0000.vtu"));
  EXPECT_TRUE(fs::exists(dir_ / "some" / "registered_0002.vtu"));
}

TEST_F(VesicaRegisterTest, WarpsACtSlice) {
  app::patient::PatientVolume ct;
  ct.labels.dims = {20, 14, 12};
  ct.labels.spacing_m = Eigen::Vector3d::Constant(0.006);
  ct.labels.labels.assign(20 * 14 * 12, 0);
  ct.hu.assign(20 * 14 * 12, 0);
  for (int k = 0; k < 12; ++k)
    for (int j = 0; j < 14; ++j)
      for (int i = 0; i < 20; ++i) ct.hu[ct.labels.Index(i, j, k)] = static_cast<std::int16_t>(10 * k);
  app::patient::WriteNiftiPatient(ct, dir_ / "ct.nii.gz", dir_ / "ct_labels.nii.gz");
  const fs::path out = dir_ / "out";
  const ToolRun run = RunTool((dir_ / "box.vtu").string() + " " + (dir_ / "points.csv").string() + " --out " +
                              out.string() + " --warp " + (dir_ / "ct.nii.gz").string() + " --slice j:6");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  for (const char* f :
       {"slice_j6_original.png", "slice_j6_warped.png", "slice_j6_warped_ct.nii.gz", "slice_j6_warped_labels.nii.gz"})
    EXPECT_TRUE(fs::exists(out / f)) << f;
  // The box moved 4 mm up: inside it, each voxel shows the CT from 4 mm lower (10 HU per 6 mm).
  const app::patient::PatientVolume warped = app::patient::ReadNiftiVolume(out / "slice_j6_warped_ct.nii.gz");
  ASSERT_EQ(warped.labels.dims[1], 1);
  const int i = 10, k = 5;
  EXPECT_NEAR(warped.hu[static_cast<size_t>(i + 20 * k)], 10.0 * (k - 4.0 / 6.0), 2.0);
}

TEST_F(VesicaRegisterTest, BadInputIsRefusedNamingFileAndLineAndNothingIsWritten) {
  const std::string mesh = (dir_ / "box.vtu").string();
  ExpectRefused(mesh + " " + WithLine(4, "0,0,nan,0.01,0.02,0,0,1,1,0").string(), "bad.csv:4: x_m is not");
  ExpectRefused(mesh + " " + WithLine(4, "0,0,0.01,0.01,0.02,0,0,0,1,0").string(), "bad.csv:4: the normal");
  ExpectRefused(mesh + " " + WithLine(40, "0,0.8,0.01,0.01,0.0,0,0,1,1,0").string(), "bad.csv:40: frame 0 after frame");
  ExpectRefused(mesh + " " + WithLine(5, "0,0,0.5,0.01,0.02,0,0,1,1,0").string(),
                "bad.csv:5: the point is more than 50 mm from the mesh");
  ExpectRefused(mesh + " " + WithLine(4, "0,0,0.01,0.01,0.02,0,0,1,1.5,0").string(), "bad.csv:4: confidence");
  ExpectRefused(mesh + " " + WithLine(2, "frame,time,x,y,z").string(), "bad.csv:2: expected the header");
  // A mesh with an inverted tet: the error names the file and the tet.
  physics::TetrahedralMesh inverted = mesh_;
  std::swap(inverted.tets(7, 0), inverted.tets(7, 1));
  app::WriteTetrahedralMesh(inverted, dir_ / "inverted.vtu");
  ExpectRefused((dir_ / "inverted.vtu").string() + " " + (dir_ / "points.csv").string(), "inverted.vtu");
}

}  // namespace
}  // namespace vesica
