#include "device/arm_supervisor.h"

#include <utility>

namespace vesica::device {

ArmSupervisor::ArmSupervisor(CanArm& arm, ArmSupervisorConfig config) : arm_(arm), config_(std::move(config)) {}

void ArmSupervisor::RequestFaultReset() { reset_requested_.store(true); }

void ArmSupervisor::Tick(fp::Nanoseconds now) {
  const std::int64_t t = now.count();
  const DeviceStatus status = arm_.Status();
  const fp::FaultCode fault = arm_.node_fault();
  std::lock_guard lock(mu_);
  if (first_tick_ns_ < 0) first_tick_ns_ = t;
  silent_too_long_ = !arm_.answered() && t - first_tick_ns_ >= config_.no_answer_after.count();

  if (reset_requested_.exchange(false)) {
    arm_.ResetFault();
    ++requested_resets_;
    last_reset_ns_ = t;
    fault_seen_ns_ = -1;
    return;
  }
  // kNodeFault is only reported while states arrive (a lost link reads kLinkLost), so a watchdog
  // fault seen here for watchdog_reset_after has outlived the gap in commands that caused it.
  if (status != DeviceStatus::kNodeFault || fault != fp::FaultCode::CommandWatchdog) {
    fault_seen_ns_ = -1;
    return;
  }
  if (fault_seen_ns_ < 0) fault_seen_ns_ = t;
  const bool settled = t - fault_seen_ns_ >= config_.watchdog_reset_after.count();
  const bool may_retry = last_reset_ns_ < 0 || t - last_reset_ns_ >= config_.reset_retry_period.count();
  if (settled && may_retry) {
    arm_.ResetFault();
    ++automatic_resets_;
    last_reset_ns_ = t;
  }
}

std::string ArmSupervisor::Describe(const ArmSupervisorConfig& config, const Seen& seen) {
  const std::string head = config.name + ": ";
  switch (seen.status) {
    case DeviceStatus::kOk:
      return head + "ok";
    case DeviceStatus::kNodeFault:
      return head + "FAULT " +
             (seen.fault == fp::FaultCode::None ? std::string("(reading the node's fault history)")
                                                : std::string(fp::to_string(seen.fault)));
    case DeviceStatus::kLinkLost:
      return head + "link lost";
    case DeviceStatus::kNotCalibrated: {
      const std::string node = std::to_string(seen.node_id);
      const std::string command =
          config.calibrate_command.empty() ? "vesica-calibrate calibrate " + node : config.calibrate_command;
      return config.name + " (node " + node + "): no valid calibration" +
             (seen.calibration_problem.empty() ? "" : " (" + seen.calibration_problem + ")") + "; run `" + command +
             "`";
    }
    case DeviceStatus::kConnecting:
      if (seen.homing) return head + "homing " + std::to_string(static_cast<int>(100.0 * seen.homing_fraction)) + "%";
      if (seen.not_homed) {
        const std::string node = std::to_string(seen.node_id);
        const std::string command = config.home_command.empty() ? "vesica-calibrate home " + node : config.home_command;
        return config.name + " (node " + node + "): not homed since power-up, its positions are not known" +
               (seen.homing_problem.empty() ? "" : " (" + seen.homing_problem + ")") +
               "; reset faults to home it again, or run `" + command + "`";
      }
      if (seen.silent_too_long) return head + "no answer from " + (config.link.empty() ? "the node" : config.link);
      return head + (seen.answered ? "connecting" : "waiting for " + (config.link.empty() ? "the node" : config.link));
    default:
      return head + std::string(ToString(seen.status));
  }
}

ArmReport ArmSupervisor::Report() const {
  ArmReport r;
  r.status = arm_.Status();
  r.fault = r.status == DeviceStatus::kNodeFault ? arm_.node_fault() : fp::FaultCode::None;
  r.link_losses = arm_.link_loss_count();
  Seen seen{r.status,
            r.fault,
            arm_.answered(),
            false,
            arm_.node_id(),
            arm_.calibration_problem(),
            arm_.homing(),
            arm_.homing_fraction(),
            arm_.node_not_homed(),
            arm_.homing_problem()};
  std::lock_guard lock(mu_);
  r.automatic_fault_resets = automatic_resets_;
  r.requested_fault_resets = requested_resets_;
  seen.silent_too_long = silent_too_long_;
  r.text = Describe(config_, seen);
  return r;
}

}  // namespace vesica::device
