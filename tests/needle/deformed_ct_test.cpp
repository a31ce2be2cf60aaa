// The CT sampled through the breathing deformation (physics/needle/deformed_ct.h): the rest CT at
// end tidal, a rib's voxel found where its pose carries it, the tumour with the liver, no jump
// when a new patient state arrives, a CT of another size refused.
#include "physics/needle/deformed_ct.h"

#include <gtest/gtest.h>

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "needle_test_patient.h"
#include "physics/patient/breathing_patient.h"
#include "physics/patient/patient_labels.h"

namespace vesica::physics {
namespace {
using needle_test::Patient;
namespace label = patient_label;

// The rest CT's trilinear interpolation, computed here on its own.
double RestTrilinear(const Eigen::Vector3d& p) {
  const LabelVolume& v = Patient().volume.labels;
  const Eigen::Vector3d idx = (v.direction * v.spacing_m.asDiagonal()).inverse() * (p - v.origin_m);
  const int i0 = static_cast<int>(std::floor(idx.x())), j0 = static_cast<int>(std::floor(idx.y())),
            k0 = static_cast<int>(std::floor(idx.z()));
  double sum = 0.0;
  for (int c = 0; c < 8; ++c) {
    const int i = i0 + (c & 1), j = j0 + ((c >> 1) & 1), k = k0 + ((c >> 2) & 1);
    const double w = ((c & 1) ? idx.x() - i0 : 1 - (idx.x() - i0)) *
                     (((c >> 1) & 1) ? idx.y() - j0 : 1 - (idx.y() - j0)) *
                     (((c >> 2) & 1) ? idx.z() - k0 : 1 - (idx.z() - k0));
    sum += w * Patient().volume.hu[v.Index(i, j, k)];
  }
  return sum;
}

TEST(DeformedCtTest, AtEndTidalItIsTheRestCt) {
  DeformedCt ct(Patient().ct);
  // Points through skin, rib, liver, diaphragm and lung, off the voxel centres.
  for (const Eigen::Vector3d& p : {Eigen::Vector3d(-0.075, 0.1051, -0.0453), Eigen::Vector3d(-0.1307, 0.0213, -0.0601),
                                   Eigen::Vector3d(-0.0743, 0.0307, -0.0441), Eigen::Vector3d(-0.1231, 0.0199, -0.0452),
                                   Eigen::Vector3d(-0.1103, 0.0187, 0.0604), Eigen::Vector3d(0.0101, 0.0, 0.0)})
    EXPECT_NEAR(ct.Sample(p).hu, RestTrilinear(p), 1e-9) << p.transpose();
  EXPECT_EQ(ct.Sample(needle_test::TumourCentre()).label, label::kTumour);
  EXPECT_EQ(ct.Sample(Eigen::Vector3d(0.0, 0.2, 0.0)).body_fraction, 0.0);  // in front of the body
}

TEST(DeformedCtTest, MovingOrgansAreFoundWhereTheyAreNow) {
  // Quiet breathing, and a thoracic scale of 4 under which ribs move further than the rib cell
  // map's reach (40 mm), so that every rib is tried.
  for (double thoracic_scale : {1.0, 4.0}) {
    BreathingPatient patient(Patient().model);
    RespirationSettings settings = Patient().model->parameters.respiration;
    settings.thoracic_scale = thoracic_scale;
    patient.SetRespiration(settings);
    patient.Update(1.0);  // peak inspiration at 0.25 Hz
    DeformedCt ct(Patient().ct);
    ct.SetPatient(patient.snapshot());
    ct.SetBlend(1.0);
    const PatientSnapshot& s = patient.snapshot();
    // Right rib 9's inner voxels (all six neighbours rib too), carried by its pose: found there,
    // with the rib's 700 HU.
    const LabelVolume& v = Patient().volume.labels;
    const std::uint8_t rib9 = label::Rib(false, 9);
    std::size_t r9 = 0;
    for (std::size_t r = 0; r < Patient().model->ribs.size(); ++r)
      if (!Patient().model->ribs[r].left && Patient().model->ribs[r].number == 9) r9 = r;
    int checked = 0;
    double moved_most = 0.0;
    for (int k = 1; k + 1 < v.dims[2]; ++k)
      for (int j = 1; j + 1 < v.dims[1]; ++j)
        for (int i = 1; i + 1 < v.dims[0]; ++i) {
          if (v.At(i, j, k) != rib9 || v.At(i - 1, j, k) != rib9 || v.At(i + 1, j, k) != rib9 ||
              v.At(i, j - 1, k) != rib9 || v.At(i, j + 1, k) != rib9 || v.At(i, j, k - 1) != rib9 ||
              v.At(i, j, k + 1) != rib9)
            continue;
          const Eigen::Vector3d moved = s.ribs[r9].Apply(v.Position(i, j, k));
          moved_most = std::max(moved_most, (moved - v.Position(i, j, k)).norm());
          const CtSample at = ct.Sample(moved);
          EXPECT_EQ(at.label, rib9);
          EXPECT_NEAR(at.hu, 700.0, 1e-6);
          ++checked;
        }
    EXPECT_GE(checked, 20);
    EXPECT_GT(moved_most, thoracic_scale > 2 ? 0.04 : 0.005) << thoracic_scale;  // it did move (that far)
    // The tumour moved with the liver; it is sampled where it went.
    EXPECT_GT((s.tumour_centre_m - needle_test::TumourCentre()).norm(), 0.005);
    EXPECT_EQ(ct.Sample(s.tumour_centre_m).label, label::kTumour);
    EXPECT_NEAR((ct.TumourCentre_m() - s.tumour_centre_m).norm(), 0.0, 1e-12);
    // Round trip through the liver's inversion.
    const Eigen::Vector3d q = ct.LiverRestPoint(s.tumour_centre_m);
    EXPECT_NEAR((ct.LiverWorldPoint(q) - s.tumour_centre_m).norm(), 0.0, 1e-5);
  }
}

TEST(DeformedCtTest, ANewStateDoesNotJump) {
  BreathingPatient patient(Patient().model);
  DeformedCt ct(Patient().ct);
  patient.Update(0.4);
  ct.SetPatient(patient.snapshot());
  ct.SetBlend(0.6);
  const Eigen::Vector3d p = needle_test::TumourCentre() + Eigen::Vector3d(0.0, 0.008, 0.0081);
  const double before = ct.Sample(p).hu;
  const Eigen::Vector3d tumour_before = ct.TumourCentre_m();
  patient.Update(0.5);
  ct.SetPatient(patient.snapshot());  // blended from where it was
  EXPECT_NEAR(ct.Sample(p).hu, before, 1e-9);
  EXPECT_NEAR((ct.TumourCentre_m() - tumour_before).norm(), 0.0, 1e-12);
  ct.SetBlend(1.0);
  EXPECT_NEAR((ct.TumourCentre_m() - patient.snapshot().tumour_centre_m).norm(), 0.0, 1e-12);
}

TEST(DeformedCtTest, ACtOfAnotherSizeIsRefused) {
  std::vector<std::int16_t> hu(10, 0);
  try {
    (void)BuildDeformedCtModel(Patient().model, hu);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("10 voxels"), std::string::npos) << e.what();
  }
  EXPECT_THROW((void)BuildDeformedCtModel(nullptr, hu), std::invalid_argument);
}

}  // namespace
}  // namespace vesica::physics
