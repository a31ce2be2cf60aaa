#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "device/calibration/calibration_abort.h"
#include "device/calibration/calibration_link.h"

namespace vesica::device::calibration {

/// One constant-velocity sweep segment: mean joint torque commanded and mean velocity.
struct FrictionSegment {
  double velocity = 0.0;  ///< rad/s or m/s (distance / time over the window)
  double torque = 0.0;    ///< N m or N, in the node's torque units
};

/// One static hold of pitch: the torques at which it broke loose upward and downward.
struct GravityHold {
  double angle_rad = 0.0;
  double breakaway_up = 0.0;    ///< N m
  double breakaway_down = 0.0;  ///< N m
  double holding() const { return 0.5 * (breakaway_up + breakaway_down); }
};

/// One hold against the reference load: where, and the torque it took less gravity's (pitch).
struct LoadHold {
  double position = 0.0;  ///< rad or m
  double torque = 0.0;    ///< N m or N, node torque units
};

struct JointCalibration {
  int direction = 1;             ///< encoder_direction
  double position_offset = 0.0;  ///< rad or m
  double current_offset_A = 0.0;
  double lower_stop = 0.0;  ///< hard stops found, in the calibrated frame
  double upper_stop = 0.0;
  double index_position = 0.0;   ///< reference index edge, calibrated frame
  double coulomb = 0.0;          ///< N m or N
  double viscous = 0.0;          ///< N m s/rad or N s/m
  double friction_offset = 0.0;  ///< constant term of the fit (pitch: mean gravity of the sweeps)
  double friction_rms = 0.0;     ///< residual of the fit
  std::vector<FrictionSegment> friction_segments;
  /// Torque-constant check: real torque per node torque unit, i.e. the motor's torque constant
  /// over the node's torque_constant[j]; 0 when not measured.
  double torque_constant_ratio = 0.0;
  std::vector<LoadHold> load_holds;
};

/// The guided hand steps' readings (raw counts as the node reports them).
struct HandSensorCalibration {
  bool roll_measured = false, jaw_measured = false, pedal_measured = false;
  std::int32_t roll_raw = 0;     ///< roll encoder with the instrument at its reference (mark up)
  double roll_offset_rad = 0.0;  ///< what the roll sensor reads at the reference, (-pi, pi]
  std::int32_t jaw_closed_raw = 0, jaw_open_raw = 0;
  std::int32_t pedal_up_raw = 0, pedal_down_raw = 0;
  int roll_attempts = 0, jaw_attempts = 0, pedal_attempts = 0;  ///< 1 when the first was taken
};

/// What a calibration found and did.
struct CalibrationResult {
  NodeIdentity identity;
  std::array<JointCalibration, 3> joint;
  double gravity_sin = 0.0;  ///< pitch holding torque = sin * sin(pitch) + cos * cos(pitch), N m
  double gravity_cos = 0.0;
  std::vector<GravityHold> gravity_holds;
  HandSensorCalibration hand;
  bool saved = false;  ///< stored in a slot on the node
  /// Set when something measured could not be stored (a node below protocol 1.3 has no place for
  /// the torque-constant correction and the hand sensors' calibration), saying so; else empty.
  std::string not_stored;
  AbortReason abort = AbortReason::kNone;  ///< why it stopped early
  std::string message;                     ///< for the technician
  std::string failed_step;
};

}  // namespace vesica::device::calibration
