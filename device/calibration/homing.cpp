// Homing after power-up: the lower hard stop for the coarse frame, the reference index for the
// count-exact one (docs/calibration.md "Homing after power-up").
#include "device/calibration/homing.h"

#include <cmath>
#include <numbers>

#include "device/calibration/servo_until.h"
#include "firmware_protocol/node/parameter_table.h"

namespace vesica::device::calibration {
namespace {

const char* kJointName[3] = {"yaw", "pitch", "insertion"};

// Every selected joint seeks its lower stop at once; the reading at rest on it, per joint.
std::array<double, 3> SeekLowerStops(CalibrationLink& link, JointServo& servo, const HomingPlan& plan) {
  std::array<double, 3> stop{};
  std::array<int, 3> still_ms{}, push_ms{};
  std::array<double, 3> push_sum{};
  std::array<bool, 3> done{};
  const double far = 4.0;  // beyond any stop: the reference keeps pulling until the stop holds it
  for (int j = 0; j < 3; ++j) {
    done[j] = !((plan.joints >> j) & 1u);
    if (done[j]) continue;
    servo.Engage(j, link.sample().position[j]);
    servo.SetTorqueLimit(j, plan.seek_torque[j]);
    servo.MoveTo(j, link.sample().position[j] - far, plan.seek_speed[j]);
  }
  ServoUntil(
      link, servo,
      [&] {
        bool all = true;
        for (int j = 0; j < 3; ++j) {
          if (done[j]) continue;
          all = false;
          const double p = link.sample().position[j];
          const bool rotary = j < 2;
          // On the stop: the reference has run well past the joint and the joint stands still.
          const bool pushing = std::abs(servo.reference(j) - p) > (rotary ? 0.05 : 5e-3) &&
                               std::abs(servo.velocity(j)) < (rotary ? 0.01 : 1e-3);
          still_ms[j] = pushing ? still_ms[j] + 1 : 0;
          if (still_ms[j] <= 100) continue;
          push_sum[j] += p;  // then averaged over 50 ms of full push
          if (++push_ms[j] < 50) continue;
          stop[j] = push_sum[j] / push_ms[j];
          servo.Engage(j, p);
          servo.MoveTo(j, stop[j] + (rotary ? 0.02 : 2e-3), plan.move_speed[j]);  // off the stop
          done[j] = true;
        }
        if (plan.progress) {
          int n = 0;
          for (int j = 0; j < 3; ++j) n += done[j] ? 1 : 0;
          plan.progress("homing", 0.4 * n / 3.0);
        }
        return all;
      },
      60.0, "homing: a lower hard stop was not found within 60 s");
  return stop;
}

}  // namespace

HomingResult HomeArm(CalibrationLink& link, const HomingPlan& plan, ArmDesign design) {
  HomingResult result;
  const double started_s = link.now_s();
  const std::string node = "node " + std::to_string(link.node_id());
  try {
    result.identity = link.Connect();
    if (result.identity.negotiated_minor < fp::kHomingMinor)
      throw CalibrationAbort(AbortReason::kProtocolTooOld,
                             node + " speaks protocol " + std::to_string(result.identity.protocol_major) + "." +
                                 std::to_string(result.identity.negotiated_minor) + "; homing needs " +
                                 std::to_string(fp::kProtocolMajor) + "." + std::to_string(fp::kHomingMinor) +
                                 " (update the arm's firmware); its positions are right only if it powered up where "
                                 "it was calibrated; nothing was moved");
    link.ClearFault();
    result.was_homed = !link.node_not_homed();
    std::array<double, 3> joint_min{}, index_position{}, spacing{};
    for (int j = 0; j < 3; ++j) {
      const auto jj = static_cast<std::uint16_t>(j);
      const double kt = link.ReadF32(fp::param::kTorqueConstant + jj);
      const double ratio = link.ReadF32(fp::param::kGearRatio + jj);
      design.nm_per_A[j] = kt * ratio;
      spacing[j] = 2.0 * std::numbers::pi / ratio;  // one index edge per motor revolution
      result.offset_before[j] = link.ReadF32(fp::param::kPositionOffset + jj);
      result.offset_after[j] = result.offset_before[j];
      joint_min[j] = link.ReadF32(fp::param::kJointMin + jj);
      index_position[j] = link.ReadF32(fp::param::kIndexPosition + jj);
    }
    if (plan.progress) plan.progress("homing", 0.0);
    link.BeginSession(plan.joints, plan.session_max_current_A);
    JointServo servo(design);
    const std::array<double, 3> stop = SeekLowerStops(link, servo, plan);
    int homed_joints = 0;
    for (int j = 0; j < 3; ++j) {
      if (!((plan.joints >> j) & 1u)) continue;
      const auto jj = static_cast<std::uint16_t>(j);
      // The stop puts the reading right to within the range margin and the stop's give.
      const double coarse_shift = (joint_min[j] - plan.range_margin[j]) - stop[j];
      double offset = result.offset_before[j] + coarse_shift;
      if (plan.has_index[j]) {
        ServoUntil(
            link, servo, [&] { return servo.arrived(j); }, 10.0, "homing: joint did not leave its stop");
        const double before = link.ReadF32(fp::param::kPositionOffset + jj);
        // The node zeroes the joint at the first edge above: the offset's change is the edge's reading.
        link.RunNodeProcedure(fp::CalibrationProcedure::FindIndex, static_cast<std::uint8_t>(1u << j),
                              plan.find_index_current_A[j], 10.0, [&] { return servo.Update(link.sample(), 1e-3); });
        const double zeroed = link.ReadF32(fp::param::kPositionOffset + jj);
        const double edge_reading = before - zeroed;
        const double edge_estimate = edge_reading + coarse_shift;
        const double k = std::round((edge_estimate - index_position[j]) / spacing[j]);
        const double edge = index_position[j] + k * spacing[j];
        if (std::abs(edge - edge_estimate) > 0.4 * spacing[j])
          throw CalibrationAbort(AbortReason::kMeasurement,
                                 std::string("homing: ") + kJointName[j] + "'s index edge is " +
                                     std::to_string(edge - edge_estimate) +
                                     " from where its stop puts it (more than 0.4 of the edge spacing): "
                                     "the stored calibration does not fit this arm; run a whole calibration");
        offset = zeroed + edge;
      }
      link.WriteF32(fp::param::kPositionOffset + jj, static_cast<float>(offset));
      result.offset_after[j] = offset;
      result.correction[j] = offset - result.offset_before[j];
      link.Cycle(servo.amps());  // a sample in the new frame
      servo.Engage(j, link.sample().position[j]);
      servo.SetTorqueLimit(j, plan.seek_torque[j]);
      servo.MoveTo(j, design.centre[j], plan.move_speed[j]);
      if (plan.progress) plan.progress("homing", 0.4 + 0.5 * ++homed_joints / 3.0);
    }
    link.DeclareHome();
    ServoUntil(
        link, servo,
        [&] {
          for (int j = 0; j < 3; ++j)
            if (((plan.joints >> j) & 1u) && !servo.arrived(j)) return false;
          return true;
        },
        30.0, "homing: the joints did not return to the centre");
    // At rest before the session ends and the joints go free.
    const double settle_until = link.now_s() + 0.3;
    ServoUntil(
        link, servo, [&] { return link.now_s() >= settle_until; }, 1.0, "timer");
    // Unsaved: the stored calibration stays; the node keeps the declared offsets in force.
    link.AbortSession();
    result.homed = true;
    if (plan.progress) plan.progress("homing", 1.0);
  } catch (const CalibrationAbort& e) {
    link.AbortSession();
    result.abort = e.reason();
    result.message = e.what();
  }
  result.bus_time_s = link.now_s() - started_s;
  return result;
}

}  // namespace vesica::device::calibration
