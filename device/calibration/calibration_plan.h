#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "device/calibration/hand_guide.h"

namespace vesica::device::calibration {

/// The steps of a calibration, in the order they run (bits of CalibrationPlan::steps).
enum CalibrationStepBit : std::uint8_t {
  kStepCurrentOffset = 1u << 0,
  kStepEncoderDirection = 1u << 1,
  kStepRange = 1u << 2,
  kStepIndex = 1u << 3,
  kStepFriction = 1u << 4,
  kStepGravity = 1u << 5,
  kAllSteps = 0x3F,  ///< a whole calibration; the checks below need a fixture and run on request
  /// Torque constant against the reference load fixture (clamped on for this step alone).
  kStepTorqueConstant = 1u << 6,
  /// Roll sensor offset, jaw handle span and pedal travel by guided hand motion (a person).
  kStepHandSensors = 1u << 7,
};

/// How a calibration moves the arm: every motion slow and current-limited. Joint order yaw,
/// pitch, insertion; rotary values in rad, N m; insertion in m, N.
struct CalibrationPlan {
  std::uint8_t joints = 0b111;  ///< joints to calibrate (bit j)
  /// Steps to run; a step left out keeps what the node has (its stored calibration), and the
  /// later steps work from that (e.g. friction alone on an arm whose range is calibrated).
  std::uint8_t steps = kAllSteps;
  double session_max_current_A = 0.6;                          ///< the node clips every command to this, > 0
  std::array<double, 3> seek_speed{0.3, 0.3, 0.03};            ///< toward a hard stop
  std::array<double, 3> seek_torque{0.15, 0.15, 1.2};          ///< pushing on a hard stop, at most
  std::array<double, 3> move_speed{0.5, 0.5, 0.05};            ///< between measurements
  std::array<double, 3> find_index_current_A{0.25, 0.3, 0.5};  ///< the node's index creep
  /// Constant-velocity sweeps, both directions each.
  std::array<std::vector<double>, 3> friction_speeds{{{0.3, 0.6, 1.2}, {0.3, 0.6, 1.2}, {0.03, 0.06, 0.12}}};
  std::array<double, 3> sweep_margin{0.25, 0.25, 0.03};   ///< sweeps keep this far from the stops
  std::array<double, 3> range_margin{0.02, 0.02, 0.002};  ///< soft limits inside the stops
  int gravity_angles = 5;                                 ///< static holds of pitch, >= 2
  double gravity_ramp_A_per_s = 0.05;                     ///< current ramp that breaks a hold loose
  /// The reference load fixture's certified stiffness (printed on it): N m/rad, N m/rad, N/m, > 0.
  std::array<double, 3> reference_stiffness{0.4, 0.4, 20.0};
  std::array<double, 3> torque_constant_span{0.25, 0.25, 0.025};  ///< holds within +- this of the centre
  int torque_constant_holds = 5;                                  ///< per joint, >= 2
  /// The guided hand steps' person (prompts with a live value); null: those steps stop at once.
  HandGuide hand_guide;
  int hand_attempts = 3;                  ///< a step whose readings fail their check this often fails
  double jaw_min_span_counts = 500;       ///< ADC counts between closed and open, at least
  double pedal_min_travel_counts = 500;   ///< ADC counts between released and pressed, at least
  double hand_prompt_timeout_s = 600;     ///< bus time a prompt waits for its answer
  std::uint32_t date_s = 0;               ///< recorded in the stored slot (Unix time)
  std::uint32_t tool_version = 0x000100;  ///< major << 16 | minor << 8 | patch
  /// Step name and fraction done (0..1), called as the calibration goes.
  std::function<void(const std::string& step, double fraction)> progress;
};

}  // namespace vesica::device::calibration
