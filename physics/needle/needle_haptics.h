#pragma once
// The biopsy needle's force on the breathing patient at the haptic rate (seed section 5; issue 34),
// and the trainee's metrics (seed 6.3). One Update per haptic tick (1 kHz) with the stylus pose;
// SetPatient whenever the physics publishes a new patient snapshot.
//
// The force, only while the tip is inside the body (seed 5.2, after Vidal et al. 2008):
//  - axial: -D k_HU I, I the Hounsfield variation crossed, the integral of |dHU/ds| along the
//    inserted needle (entry point to tip) through the breathing deformation (DeformedCt): a step
//    of k_HU |HU_a - HU_b| at every tissue plane the needle has crossed. Before the capsule is
//    perforated the integral stops at the capsule (the liver is pushed ahead of the tip).
//  - lateral (eq. 13's intent): -k_lat r(s) e, e = (P - P0) - ((P - P0).D0) D0 the tip's deviation
//    from the initial insertion line P0 + s D0, r(s) a smoothstep from 0 to 1 over the first
//    lateral_onset_m of insertion s = (P - P0).D0. The printed eq. 13, (P - P0) sin(D0 / (P - P0)),
//    divides by a vector; we read the sine as that of the angle between D0 and P - P0, so its
//    magnitude |P - P0| sin(angle) = |e|: a force growing with the deviation, pulling back to the line.
//  - capsule (eq. 14): -D F_n(d), d the depth past the capsule's undeformed (breathing only)
//    surface; before puncture the capsule is pushed ahead of the tip (capsule_push(), for
//    BreathingPatient::PushCapsule: the three nearest capsule elements move with the tip).
//  - grip: once perforated, the liver holds the needle at its hole and breathing moves the hole:
//    sideways a spring to the hole, along the needle a spring that slips past grip_slip_force_N
//    (stick-slip friction). So respiration under an inserted needle pulls it along its line.
// The sum is bounded by max_force_N (the device's capability). The patient's state is blended
// from the previous snapshot to the latest over blend_s, so nothing jumps at a physics update.
//
// Bad input (a NaN pose, a zero direction, a non-finite time) throws std::invalid_argument and
// leaves every state as it was (the repository's convention in physics/).

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <vector>

#include "physics/needle/biopsy_metrics.h"
#include "physics/needle/capsule_force.h"
#include "physics/needle/deformed_ct.h"
#include "physics/needle/needle_pose.h"

namespace vesica::physics {

struct NeedleHapticsParameters {
  double axial_N_per_HU = 7e-4;    ///< >= 0: axial force per Hounsfield unit crossed (1400 HU through a wall: 1 N)
  double sample_step_m = 0.0;      ///< >= 0: along the needle; 0 = half the CT's smallest voxel
  double lateral_onset_m = 0.005;  ///< > 0: the lateral constraint grows in over these first mm
  double lateral_stiffness_N_per_m = 300.0;  ///< >= 0: once inserted past the onset
  CapsuleForceParameters capsule = FittedCapsuleForceParameters();
  double grip_lateral_stiffness_N_per_m = 150.0;  ///< >= 0: the liver's hole, sideways
  double grip_axial_stiffness_N_per_m = 300.0;    ///< > 0: the hole along the needle, until it slips
  double grip_slip_force_N = 0.3;                 ///< >= 0: the hole's friction limit along the needle
  double max_force_N = 3.3;                       ///< > 0: the device's peak force (Phantom Omni: 3.3 N)
  double blend_s = 0.02;                          ///< > 0: the patient's update period, blended over
};
/// Throws std::invalid_argument naming the field.
void ValidateNeedleHapticsParameters(const NeedleHapticsParameters& p);

enum class CapsuleContact : std::uint8_t { kNone, kPushing, kPunctured };

struct NeedleForces {
  Eigen::Vector3d total_N = Eigen::Vector3d::Zero();  ///< what the device renders (bounded)
  Eigen::Vector3d axial_N = Eigen::Vector3d::Zero();
  Eigen::Vector3d lateral_N = Eigen::Vector3d::Zero();
  Eigen::Vector3d capsule_N = Eigen::Vector3d::Zero();
  Eigen::Vector3d grip_N = Eigen::Vector3d::Zero();
  bool inside = false;       ///< the tip is in the body (else every force is zero)
  bool clamped = false;      ///< the sum exceeded max_force_N and was scaled down to it
  double hu_crossed = 0.0;   ///< I: the Hounsfield variation crossed, HU
  double inserted_m = 0.0;   ///< s = (P - P0).D0
  double deviation_m = 0.0;  ///< |e|, the tip's distance from the insertion line
  CapsuleContact capsule = CapsuleContact::kNone;
  double capsule_depth_m = 0.0;                                 ///< d of eq. 14 (0 without contact)
  double capsule_force_N = 0.0;                                 ///< F_n(d)
  Eigen::Vector3d capsule_contact_m = Eigen::Vector3d::Zero();  ///< the capsule's undeformed point under the tip, now
  std::uint8_t tip_label = 0;                                   ///< what the tip is in (patient_label)
};

/// What the needle asks of the patient: push the three capsule elements nearest surface_m by
/// displacement_m (BreathingPatient::PushCapsule), or release them.
struct CapsulePush {
  bool active = false;
  Eigen::Vector3d surface_m = Eigen::Vector3d::Zero();
  Eigen::Vector3d displacement_m = Eigen::Vector3d::Zero();
};
/// Where the pushed capsule elements are in a snapshot (the deformation drawn): up to three.
[[nodiscard]] std::vector<Eigen::Vector3d> PushedCapsulePoints(const PatientSnapshot& snapshot);

class NeedleHaptics {
 public:
  /// start_s: when the task starts (the time metric counts from it).
  NeedleHaptics(std::shared_ptr<const DeformedCtModel> ct, const NeedleHapticsParameters& parameters = {},
                double start_s = 0.0);

  /// A new patient state, received at now_s; blended in over blend_s.
  void SetPatient(const PatientSnapshot& snapshot, double now_s);
  /// One haptic tick. Throws std::invalid_argument (state unchanged) for a bad pose or time.
  const NeedleForces& Update(const NeedlePose& pose, double now_s);
  /// The stylus' biopsy button: samples at the tip of the last Update. The first sample is the
  /// task's; later ones are returned and not recorded.
  BiopsySample TakeBiopsy(double now_s);

  [[nodiscard]] const NeedleForces& forces() const { return forces_; }
  [[nodiscard]] const BiopsyMetrics& metrics() const { return metrics_; }
  [[nodiscard]] CapsulePush capsule_push() const { return push_; }
  [[nodiscard]] const DeformedCt& ct() const { return ct_; }
  [[nodiscard]] const NeedleHapticsParameters& parameters() const { return parameters_; }

 private:
  void Withdrawn();
  void CountNoGo(const Eigen::Vector3d& from, const Eigen::Vector3d& to, const CtSample& at_to);
  double HounsfieldCrossed(const Eigen::Vector3d& entry, const Eigen::Vector3d& direction, double length_m) const;

  NeedleHapticsParameters parameters_;
  double step_m_ = 0.001;
  DeformedCt ct_;
  double patient_time_s_ = 0.0;
  NeedleForces forces_;
  BiopsyMetrics metrics_;
  CapsulePush push_;
  // The current insertion.
  bool inside_ = false;
  Eigen::Vector3d p0_ = Eigen::Vector3d::Zero(), d0_ = Eigen::Vector3d::UnitX();
  Eigen::Vector3d last_tip_ = Eigen::Vector3d::Zero();
  bool any_pose_ = false;
  int last_no_go_ = -1;
  Eigen::Vector3d contact_rest_m_ = Eigen::Vector3d::Zero();  ///< the capsule's point, liver rest frame
  double grip_stick_m_ = 0.0;  ///< where along the needle the hole holds it (relative to the tip)
};

}  // namespace vesica::physics
