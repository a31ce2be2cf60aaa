#pragma once
// The synthetic patient of issue 33 for the needle's tests, built once, and the scripted paths
// through it (found by reading its label map along lines; docs/needle.md).
#include <Eigen/Core>
#include <memory>

#include "app/patient/synthetic_patient.h"
#include "physics/needle/deformed_ct.h"
#include "physics/patient/breathing_patient_model.h"

namespace vesica::physics::needle_test {

struct TestPatient {
  app::patient::PatientVolume volume;
  std::shared_ptr<const BreathingPatientModel> model;
  std::shared_ptr<const DeformedCtModel> ct;
};
inline const TestPatient& Patient() {
  static const TestPatient patient = [] {
    TestPatient p;
    p.volume = app::patient::GenerateSyntheticPatient();
    p.model = BuildBreathingPatientModel(p.volume.labels);
    p.ct = BuildDeformedCtModel(p.model, p.volume.hu);
    return p;
  }();
  return patient;
}

inline Eigen::Vector3d TumourCentre() {
  const app::patient::SyntheticTumour t;
  return {t.x_m, t.y_m, t.z_m};
}
// Anterior, between costal cartilages 7 and 8, straight back to the tumour's centre, on voxel
// centres: air, skin, fat, intercostal muscle, capsule, liver, tumour.
inline const Eigen::Vector3d kAnteriorStart(-0.075, 0.14, -0.045);
inline const Eigen::Vector3d kAnteriorDirection(0.0, -1.0, 0.0);
// Subcostal, from below the costal margin up (35 degrees) to the tumour's centre: air, skin, fat,
// abdominal muscle, capsule, liver, tumour; breathing moves the liver along this needle.
inline const Eigen::Vector3d kSubcostalStart(-0.075, 0.14, -0.13);
// From the right flank at z = -60 mm towards the tumour: through rib 9 (bone), then the liver.
inline const Eigen::Vector3d kRibStart(-0.20, 0.02, -0.06);
// From the right flank at z = +60 mm, level: through skin, fat and muscle into the lung.
inline const Eigen::Vector3d kLungStart(-0.20, 0.02, 0.06);

}  // namespace vesica::physics::needle_test
