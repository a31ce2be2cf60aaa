#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <string>

#include "device/calibration/calibration_abort.h"
#include "device/calibration/calibration_link.h"
#include "device/calibration/joint_servo.h"

namespace vesica::device::calibration {

/// How homing moves the arm after power-up: slow and current-limited, as a calibration. Joint
/// order yaw, pitch, insertion; rotary values in rad, N m; insertion in m, N.
struct HomingPlan {
  std::uint8_t joints = 0b111;                                 ///< joints to home (bit j)
  double session_max_current_A = 0.6;                          ///< the node clips every command to this, > 0
  std::array<double, 3> seek_speed{0.3, 0.3, 0.03};            ///< toward the lower hard stop
  std::array<double, 3> seek_torque{0.15, 0.15, 1.2};          ///< pushing on it, at most
  std::array<double, 3> move_speed{0.5, 0.5, 0.05};            ///< back to the centre
  std::array<double, 3> find_index_current_A{0.25, 0.3, 0.5};  ///< the node's index creep
  /// Where the calibration put the soft range inside the stops (its plan's range_margin): the
  /// lower stop is joint_min less this.
  std::array<double, 3> range_margin{0.02, 0.02, 0.002};
  /// A joint without an index homes on its lower stop alone (to within the stop's give).
  std::array<bool, 3> has_index{true, true, true};
  /// "homing" and the fraction done (0..1), as it goes.
  std::function<void(const std::string& step, double fraction)> progress;
};

/// What homing found, per joint: the position offset before (the stored one, right only if the
/// arm powered up where it was calibrated) and after, and how far the reading was off.
struct HomingResult {
  NodeIdentity identity;
  bool homed = false;
  bool was_homed = false;  ///< the node said it was homed already (nothing moved)
  std::array<double, 3> offset_before{};
  std::array<double, 3> offset_after{};
  std::array<double, 3> correction{};  ///< offset_after - offset_before: the move while off
  double bus_time_s = 0.0;
  AbortReason abort = AbortReason::kNone;
  std::string message;  ///< why it stopped, for the technician
};

/// Homes one arm after power-up (protocol 1.4): Hello (a node below 1.4 cannot be homed:
/// kProtocolTooOld, nothing moves), fault reset, the node's calibration session; every selected
/// joint seeks its lower hard stop (slow, torque-limited), which puts the reading within the
/// calibration's range margin of the truth; then the node's find-index creeps up from the stop to
/// the first index edge, and the edge's reading names which of the evenly spaced edges it is
/// (the stored index_position plus a whole number of spacings, 2 pi / gear_ratio): the offset is
/// then exact to an encoder count. The offsets are declared home (CalibrationProcedure::Home), the
/// joints return to the centre and the session ends unsaved: the stored calibration stays as it
/// was, in this power-up's frame. Any stop (fault, E-stop, link loss, abort request) ends the
/// session: the arm is left disabled and not homed.
HomingResult HomeArm(CalibrationLink& link, const HomingPlan& plan, ArmDesign design = {});

}  // namespace vesica::device::calibration
