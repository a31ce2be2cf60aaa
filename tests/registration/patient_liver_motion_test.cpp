// The biopsy patient's liver driven by a registration result instead of ChainMail (issue 35):
// BreathingPatient::DriveLiver with physics/registration's MakePointMotion.

#include <gtest/gtest.h>

#include "app/patient/synthetic_patient.h"
#include "physics/mesh/primitives.h"
#include "physics/patient/breathing_patient.h"
#include "physics/registration/displacement_series.h"

namespace vesica::physics {
namespace {

TEST(PatientLiverMotionTest, TheLiverFollowsARegisteredSeriesAndChainMailAgainWithout) {
  const std::shared_ptr<const BreathingPatientModel> model =
      BuildBreathingPatientModel(app::patient::GenerateSyntheticPatient({.spacing_m = 0.004}).labels);
  const std::vector<Eigen::Vector3d>& rest = model->liver.lattice.rest_m;
  ASSERT_FALSE(rest.empty());
  // A box mesh around the liver carries a registered motion: 12 mm caudal, 3 mm anterior at t = 2 s.
  Eigen::Vector3d lo = rest[0], hi = rest[0];
  for (const auto& p : rest) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  TetrahedralMesh box = MakeBoxTetMesh(hi - lo + Eigen::Vector3d::Constant(0.02), Eigen::Vector3i(6, 5, 4));
  box.vertices.rowwise() += (lo - Eigen::Vector3d::Constant(0.01)).transpose();
  const Eigen::Vector3d peak(0.0, 0.003, -0.012);
  Vertices moved = Vertices::Zero(box.num_vertices(), 3);
  moved.rowwise() += peak.transpose();
  const auto series = std::make_shared<const DisplacementSeries>(
      box, std::vector<DisplacementFrame>{{0.0, Vertices::Zero(box.num_vertices(), 3)}, {2.0, moved}});

  BreathingPatient patient(model);
  patient.DriveLiver(MakePointMotion(series, rest));
  patient.Update(1.0);  // half way to the peak
  const PatientSnapshot& driven = patient.snapshot();
  ASSERT_EQ(driven.liver_m.size(), rest.size());
  for (size_t i = 0; i < rest.size(); ++i)
    ASSERT_TRUE(driven.liver_m[i].isApprox(rest[i] + 0.5 * peak, 1e-9)) << "element " << i;
  if (model->liver.has_tumour) {
    EXPECT_TRUE(driven.tumour_centre_m.isApprox(model->liver.tumour_centre_m + 0.5 * peak, 1e-9));
  }
  patient.Update(3.0);  // the replay's period is 4 s: 3 s is half way back
  EXPECT_TRUE(patient.snapshot().liver_m[0].isApprox(rest[0] + 0.5 * peak, 1e-9));

  // Without the motion, ChainMail moves the liver again, and not as the series did.
  // Over a breath, it moves elements by millimetres, and not all alike (the series moved them alike).
  patient.DriveLiver({});
  double largest = 0.0, spread = 0.0;
  for (double t = 4.25; t < 10.0; t += 0.25) {
    patient.Update(t);
    const Eigen::Vector3d first = patient.snapshot().liver_m[0] - rest[0];
    for (size_t i = 0; i < rest.size(); ++i) {
      const Eigen::Vector3d u = patient.snapshot().liver_m[i] - rest[i];
      largest = std::max(largest, u.norm());
      spread = std::max(spread, (u - first).norm());
    }
  }
  EXPECT_GT(largest, 1e-3);
  EXPECT_GT(spread, 1e-4);

  // A motion of the wrong size is refused.
  patient.DriveLiver([](double) { return std::vector<Eigen::Vector3d>(3); });
  EXPECT_THROW(patient.Update(10.0), std::invalid_argument);
}

}  // namespace
}  // namespace vesica::physics
