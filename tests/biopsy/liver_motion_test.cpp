// A registration result drives the biopsy patient's liver (issue 35's scenario setting): the
// committed biopsy replayed while the liver follows a registered motion. A motion that holds the
// liver 4 mm cranial of its scanned place puts the tumour's centre 4 mm off the needle's line, so
// the sample taken 7 mm short of the centre lands sqrt(7^2 + 4^2) = 8.06 mm from it.

#include "app/biopsy/liver_motion.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <fstream>

#include "app/biopsy/biopsy_replay.h"
#include "app/mesh_io/mesh_io.h"
#include "device/stylus/stylus_recording.h"
#include "physics/mesh/primitives.h"

namespace vesica::app::biopsy {
namespace {

TEST(LiverMotionTest, ARegisteredShiftOfTheLiverMovesTheTumourUnderTheNeedle) {
  const std::filesystem::path data = VESICA_DATA_DIR;
  const auto patient = LoadCommittedBiopsyPatient(data / "patients");
  // A box of tets around the liver, as vesica-register would have registered, and its
  // displacement.csv: two frames, both 4 mm cranial (the motion holds still).
  const std::vector<Eigen::Vector3d>& rest = patient->model->liver.lattice.rest_m;
  Eigen::Vector3d lo = rest[0], hi = rest[0];
  for (const auto& p : rest) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  physics::TetrahedralMesh box = physics::MakeBoxTetMesh(hi - lo + Eigen::Vector3d::Constant(0.04), {5, 4, 4});
  box.vertices.rowwise() += (lo - Eigen::Vector3d::Constant(0.02)).transpose();
  const auto dir = std::filesystem::temp_directory_path() / ("vesica_liver_motion_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  WriteTetrahedralMesh(box, dir / "liver.vtu");
  {
    std::ofstream csv(dir / "displacement.csv");
    csv << "frame,time_s,node,ux_m,uy_m,uz_m\n";
    for (int frame = 0; frame < 2; ++frame)
      for (int node = 0; node < box.num_vertices(); ++node)
        csv << frame << ',' << frame * 0.5 << ',' << node << ",0,0,0.004\n";
  }
  BiopsySessionSettings settings;
  settings.liver_motion = LoadLiverMotion(*patient, dir / "liver.vtu", dir / "displacement.csv");
  std::filesystem::remove_all(dir);

  const auto recording = device::ReadStylusRecording(data / "recordings" / "biopsy.csv");
  const BiopsyReplayResult breathing = ReplayBiopsy(patient, recording);
  const BiopsyReplayResult registered = ReplayBiopsy(patient, recording, settings);
  ASSERT_TRUE(breathing.metrics.biopsy_sampled && registered.metrics.biopsy_sampled);
  EXPECT_NEAR(breathing.metrics.sample_distance_m, 0.007, 2e-4);
  EXPECT_NEAR(registered.metrics.sample_distance_m, std::sqrt(0.007 * 0.007 + 0.004 * 0.004), 2e-4);
  EXPECT_NEAR(registered.needle_metrics.sample->tumour_centre_m.z() - patient->model->liver.tumour_centre_m.z(), 0.004,
              1e-9);
}

TEST(LiverMotionTest, AMissingSeriesNamesTheFile) {
  const auto patient = LoadCommittedBiopsyPatient(std::filesystem::path(VESICA_DATA_DIR) / "patients");
  try {
    LoadLiverMotion(*patient, "/nonexistent/liver.vtu", "/nonexistent/displacement.csv");
    FAIL() << "loaded a motion from nothing";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/liver.vtu"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace vesica::app::biopsy
