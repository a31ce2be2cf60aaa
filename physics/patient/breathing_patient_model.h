#pragma once
// The const part of the breathing patient (STYLE.md 2), built once from a label map: the ribs'
// rotation centres and axes (seed 4.3), the diaphragm's lattice with its tendon and its fixed spine
// attachment (4.4), the liver's lattice and its coupling to the diaphragm (4.5). What moves per
// update is in BreathingPatient.
//
// Organs the seed leaves still stay still: skin, fat, muscle, spine, sternum, lungs (their base is
// the diaphragm's upper surface, which the pleura holds to it: the lungs are where the liver must
// not go), costophrenic recesses, gallbladder, colon. Costal cartilage and intercostal bundles move
// with their rib; the tumour with the liver.

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <vector>

#include "physics/patient/block_lattice.h"
#include "physics/patient/chain_mail.h"
#include "physics/patient/label_volume.h"
#include "physics/patient/respiration_signal.h"
#include "physics/patient/rib_motion.h"

namespace vesica::physics {

struct BreathingPatientParameters {
  RespirationSettings respiration;
  double diaphragm_block_m = 0.006;                   ///< diaphragm lattice spacing (rounded to whole voxels)
  double liver_block_m = 0.008;                       ///< liver lattice spacing
  ChainMailParameters diaphragm_mail{0.5, 1.5, 0.5};  ///< a thin muscle sheet that contracts: loose
  ChainMailParameters liver_mail{0.92, 1.08, 0.08};   ///< parenchyma: stiffer
  double coupling_threshold_m = 0.005;                ///< seed 4.5: liver within 5 mm of the diaphragm is coupled
  double coupling_stiffness_N_per_m = 200.0;          ///< per coupled lattice element, the ligaments' pull
  double liver_support_stiffness_N_per_m = 10.0;      ///< per coupled element, what holds the liver below
  double under_radius_m = 0.006;     ///< a diaphragm element this close sideways lies over a liver element
  double under_clearance_m = 0.003;  ///< the liver keeps this far below the diaphragm's mid-surface (or its rest gap)
};
/// Throws std::invalid_argument naming the field.
void ValidateBreathingPatientParameters(const BreathingPatientParameters& p);

struct DiaphragmModel {
  BlockLattice lattice;
  std::shared_ptr<ChainMail> mail;         ///< links and bounds; Move is const in effect (scratch only)
  std::vector<int> tendon;                 ///< elements of the central tendon: translate rigidly (eq. 12)
  std::vector<int> spine_attachment;       ///< fixed elements (touching the spine: the crura)
  std::vector<std::uint8_t> pleural;       ///< per element: lung or costophrenic recess touches it (from above)
  double max_tendon_displacement_m = 0.0;  ///< the farthest the tendon can go before the fixed crura would move
  /// How far each element can rise (z) above the crura / above the tendon before either must move.
  std::vector<double> rise_over_crura_m, rise_over_tendon_m;
  std::vector<int> held;  ///< tendon and crura: the liver cannot lift them
};

struct LiverCoupling {
  int liver_element = 0;
  std::vector<int> diaphragm_elements;  ///< within the threshold (voxel to voxel)
  std::vector<float> weights;           ///< sum 1
};

struct LiverModel {
  BlockLattice lattice;
  std::shared_ptr<ChainMail> mail;
  std::vector<LiverCoupling> coupling;
  std::vector<int> capsule;  ///< surface elements (fewer than 26 neighbours): where a needle can push
  /// The pleural diaphragm above each liver element (within under_radius_m sideways), CSR by liver
  /// element: the liver stays under it (the lungs lie beyond), by its rest gap less a clearance.
  std::vector<int> under_first;
  std::vector<int> under_diaphragm;
  std::vector<double> under_allowance_m;  ///< how far the element may rise above the diaphragm's own rise
  Eigen::Vector3d tumour_centre_m = Eigen::Vector3d::Zero();
  LatticeEmbedding tumour;  ///< the tumour's centre, carried with the lattice
  bool has_tumour = false;
};

struct BreathingPatientModel {
  BreathingPatientParameters parameters;
  LabelVolume volume;  ///< the label map it was built from (physics' view of the patient)
  SpineAxis spine;
  std::vector<RibModel> ribs;  ///< those present, right 1-12 then left 1-12
  DiaphragmModel diaphragm;
  LiverModel liver;
};

/// Builds the model. Throws std::invalid_argument with the reason (no liver, no diaphragm, no
/// spine, a diaphragm that does not reach the spine or the liver, a degenerate rib).
[[nodiscard]] std::shared_ptr<const BreathingPatientModel> BuildBreathingPatientModel(
    LabelVolume volume, const BreathingPatientParameters& parameters = {});

}  // namespace vesica::physics
