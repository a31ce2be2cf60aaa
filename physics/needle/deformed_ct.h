#pragma once
// The patient's CT as it is now, breathing (seed 5.2: "force is computed using the initial 3D CT
// scan data"; issue 34: sampled through the respiratory deformation, not at the rest position).
//
// A world point p is mapped back to the rest volume by each moving body's current motion: a rib
// (with its cartilage and intercostal bundle) by the inverse of its rigid pose, the liver and the
// diaphragm by inverting their ChainMail displacement (trilinear between lattice elements, a few
// fixed-point steps q = p - u(q)). What each body covers at its rest point is composited over the
// still organs (skin, fat, muscle, lungs, ...) read at p itself, weighted by trilinear occupancy,
// so the sampled Hounsfield field is continuous in space and in time and equals the rest CT's
// trilinear interpolation at end tidal.
//
// Between two patient updates the haptic loop blends the previous and the latest state
// (SetBlend), so that nothing it samples jumps when the physics publishes a new snapshot.

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "physics/patient/breathing_patient.h"
#include "physics/patient/breathing_patient_model.h"

namespace vesica::physics {

/// What the CT holds at one world point now.
struct CtSample {
  double hu = -1000.0;           ///< Hounsfield units, trilinear through the deformation
  std::uint8_t label = 0;        ///< patient_label value of the structure there (nearest voxel)
  double body_fraction = 0.0;    ///< [0, 1]: trilinear share of voxels inside the body (skin and in)
  double liver_occupancy = 0.0;  ///< [0, 1]: trilinear share of liver voxels at the liver's rest point
};

/// The const part: per-voxel body of each moving organ, still organs' HU, bounding boxes.
struct DeformedCtModel {
  std::shared_ptr<const BreathingPatientModel> patient;
  std::vector<float> hu;           ///< the CT, same grid as patient->volume
  std::vector<std::uint8_t> body;  ///< per voxel: 0 still, 1 liver, 2 diaphragm, 3 + r rib r (model order)
  Eigen::Matrix3d to_index = Eigen::Matrix3d::Identity();  ///< world offset from the origin -> voxel index
  Eigen::Vector3d liver_lo_m, liver_hi_m, diaphragm_lo_m, diaphragm_hi_m;  ///< rest bounding boxes
  std::vector<Eigen::Vector3d> rib_lo_m, rib_hi_m;                         ///< per rib, its voxels' rest bounding box
  /// Per block of the liver's / diaphragm's lattice grid, how many blocks (Chebyshev, capped at
  /// 255) to the nearest block with an element: a point whose block is further than the organ's
  /// largest displacement cannot be in it, and its inversion is skipped.
  std::vector<std::uint8_t> liver_block_reach, diaphragm_block_reach;
  /// Per cube of kRibCellVoxels^3 voxels, a bit per rib (model order) whose voxels lie in it or in
  /// a touching cube: a rib's rest point outside its cells is skipped before any voxel is read.
  static constexpr int kRibCellVoxels = 4;
  std::array<int, 3> rib_cell_dims{0, 0, 0};
  std::vector<std::uint32_t> rib_cells;
  /// Per cell, the ribs (bits) with a voxel within kRibReach_m of it: a rib that has moved less
  /// than that can only be at a point whose cell lists it, so the others are not even turned.
  static constexpr double kRibReach_m = 0.04;
  std::vector<std::uint32_t> rib_reach_cells;
  double min_spacing_m = 0.0;
};
inline constexpr std::uint8_t kStillBody = 0, kLiverBody = 1, kDiaphragmBody = 2, kFirstRibBody = 3;

/// Builds the model. hu: Hounsfield units on the patient's label grid (i fastest). Throws
/// std::invalid_argument when there is no patient or hu does not match the grid's size.
[[nodiscard]] std::shared_ptr<const DeformedCtModel> BuildDeformedCtModel(
    std::shared_ptr<const BreathingPatientModel> patient, const std::vector<std::int16_t>& hu);

class DeformedCt {
 public:
  explicit DeformedCt(std::shared_ptr<const DeformedCtModel> model);

  /// Takes a new patient state. The state blended now (SetBlend's) becomes the previous one, so
  /// the sampled field does not jump; SetBlend(0) right after gives exactly what was sampled before.
  void SetPatient(const PatientSnapshot& snapshot);
  /// w in [0, 1]: 0 the previous state, 1 the latest. Clamped.
  void SetBlend(double w);

  /// Sampling many points close together (along a needle), the displacement found at one point
  /// starts the inversion at the next: one fixed-point step instead of three.
  struct SampleHint {
    bool liver = false, diaphragm = false;
    Eigen::Vector3d u_liver_m = Eigen::Vector3d::Zero(), u_diaphragm_m = Eigen::Vector3d::Zero();
  };
  [[nodiscard]] CtSample Sample(const Eigen::Vector3d& p_W, SampleHint* hint = nullptr) const;
  /// The liver's rest point now at p_W (inverting its breathing displacement).
  [[nodiscard]] Eigen::Vector3d LiverRestPoint(const Eigen::Vector3d& p_W) const;
  /// Where the liver's rest point q is now.
  [[nodiscard]] Eigen::Vector3d LiverWorldPoint(const Eigen::Vector3d& q_rest) const;
  [[nodiscard]] Eigen::Vector3d TumourCentre_m() const;
  [[nodiscard]] const DeformedCtModel& model() const { return *model_; }

 private:
  struct BodyState {  // one of two blended states
    std::vector<Eigen::Vector3d> u_liver, u_diaphragm;
    std::vector<Eigen::Matrix3d> rib_rotation;
    Eigen::Vector3d tumour_m = Eigen::Vector3d::Zero();
    double max_u_m = 0.0;
  };
  Eigen::Vector3d LatticeDisplacement(const BlockLattice& lattice, const std::vector<Eigen::Vector3d>& u_prev,
                                      const std::vector<Eigen::Vector3d>& u_now, const Eigen::Vector3d& q) const;
  /// q with q + u(q) = p; warm: the displacement near p to start from (updated to the one found).
  Eigen::Vector3d InvertLattice(const BlockLattice& lattice, const std::vector<Eigen::Vector3d>& u_prev,
                                const std::vector<Eigen::Vector3d>& u_now, const Eigen::Vector3d& p,
                                bool* warm_valid = nullptr, Eigen::Vector3d* warm_u = nullptr) const;
  /// Could the organ of this lattice be at p now (within its largest displacement)?
  [[nodiscard]] bool MayBeNear(const BlockLattice& lattice, const std::vector<std::uint8_t>& reach,
                               const Eigen::Vector3d& p) const;

  std::shared_ptr<const DeformedCtModel> model_;
  BodyState prev_, now_;
  double w_ = 1.0;
  // Blended rib poses and boxes (at SetBlend): p_rest = centre + R^T (p - centre).
  std::vector<Eigen::Matrix3d> rib_rotation_;
  std::vector<Eigen::Vector3d> rib_box_lo_, rib_box_hi_;
  bool ribs_within_reach_ = true;  ///< every rib has moved less than kRibReach_m (rib_reach_cells holds)
  double max_u_m_ = 0.0;
};

}  // namespace vesica::physics
