#include "device/can_arm.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <thread>
#include <variant>

#include "firmware_protocol/node/parameter_table.h"

namespace vesica::device {
namespace {

std::int64_t Ns(fp::Nanoseconds t) { return t.count(); }

constexpr std::int64_t kCalibrationReadSpacing_ns = 2'000'000;

DeviceCapabilities MakeCapabilities(const CanArmConfig& c) {
  DeviceCapabilities caps;
  caps.model_name = c.model_name;
  caps.joint_count = 4;
  caps.position_dof = 3;
  caps.rotation_dof = 3;  // yaw, pitch and roll give the full shaft orientation
  caps.force_dof = 3;
  caps.torque_dof = 0;
  caps.has_gripper = true;
  caps.button_count = 2;  // pedal, handle button
  caps.max_force_N = c.actuation.max_tip_force_N;
  caps.max_stiffness_N_per_m = 1000.0;
  caps.workspace_radius_m = 0.25;
  caps.servo_rate_hz = 1000.0;
  return caps;
}

}  // namespace

CanArm::CanArm(fp::Transport& transport, const CanArmConfig& config)
    : transport_(transport),
      config_(config),
      capabilities_(MakeCapabilities(config)),
      link_(config.loss_timeout.count()) {}

CanArm::~CanArm() {
  std::lock_guard lock(mu_);  // Tick() may not collect the run meanwhile
  StopHoming();
}

void CanArm::StopHoming() {
  {
    std::lock_guard lock(homing_link_mu_);
    if (homing_link_) homing_link_->RequestAbort();
  }
  if (homing_thread_.joinable()) homing_thread_.join();
}

DeviceStatus CanArm::Open() {
  std::lock_guard lock(mu_);
  if (phase_ != Phase::kClosed) return DeviceStatus::kAlreadyOpen;
  if (const std::string_view bad = config_.actuation.FirstInvalidField(); !bad.empty()) {
    last_error_ = "CanArmConfig.actuation." + std::string(bad) + " must be finite and > 0";
    return DeviceStatus::kInvalidArgument;
  }
  if (config_.node_id < 1 || config_.node_id > fp::kMaxNodeId) {
    last_error_ = "CanArmConfig.node_id must be 1..127, got " + std::to_string(config_.node_id);
    return DeviceStatus::kInvalidArgument;
  }
  if (config_.loss_timeout.count() <= 0 || !(config_.velocity_filter_hz > 0.0) || !(config_.force_ramp_s >= 0.0) ||
      config_.calibration_recheck.count() <= 0) {
    last_error_ = "CanArmConfig: loss_timeout, velocity_filter_hz, calibration_recheck must be > 0, force_ramp_s >= 0";
    return DeviceStatus::kInvalidArgument;
  }
  // The node refuses a watchdog outside its parameter range and keeps its own (3 ms), which a
  // host without real-time scheduling trips many times a minute: refuse it here, by name.
  const fp::ParameterSpec* wd = fp::find_parameter(fp::param::kWatchdogTimeout_us);
  const auto wd_us = static_cast<double>(config_.node_watchdog_timeout.count());
  if (wd_us != 0.0 && (wd_us < wd->min || wd_us > wd->max)) {
    last_error_ = "CanArmConfig.node_watchdog_timeout must be 0 (keep the node's) or " +
                  std::to_string(static_cast<long>(wd->min)) + ".." + std::to_string(static_cast<long>(wd->max)) +
                  " us, got " + std::to_string(config_.node_watchdog_timeout.count()) + " us";
    return DeviceStatus::kInvalidArgument;
  }
  link_ = LinkMonitor(config_.loss_timeout.count());
  state_sequence_.reset();
  calibration_reader_.Restart();
  calibration_read_ns_ = -1;
  negotiated_ = false;
  watchdog_configured_ = config_.node_watchdog_timeout.count() == 0;
  node_enabled_ = false;
  node_fault_ = fp::FaultCode::None;
  enabled_since_ns_ = -1;
  last_handshake_ns_ = -1;
  last_tick_ns_ = -1;
  request_sent_ns_ = -1;
  phase_ = Phase::kConnecting;
  return DeviceStatus::kConnecting;
}

void CanArm::Close() {
  std::lock_guard lock(mu_);
  StopHoming();  // the node ends its session: the arm is left disabled
  if (phase_ == Phase::kClosed) return;
  Send(fp::Control{config_.node_id, control_counter_++, fp::ControlCommand::Disable}, transport_.now());
  phase_ = Phase::kClosed;
}

DeviceStatus CanArm::StatusLocked() const {
  if (phase_ == Phase::kClosed) return DeviceStatus::kNotOpen;
  if (link_.ever_seen() && !link_.up()) return DeviceStatus::kLinkLost;
  if (phase_ == Phase::kFault) return DeviceStatus::kNodeFault;
  if (phase_ == Phase::kRunning) return DeviceStatus::kOk;
  if (calibration_reader_.state() == NodeCalibrationReader::State::kInvalid) return DeviceStatus::kNotCalibrated;
  return DeviceStatus::kConnecting;
}

DeviceStatus CanArm::Status() const {
  std::lock_guard lock(mu_);
  return StatusLocked();
}

DeviceStatus CanArm::SetTipForce(const Eigen::Vector3d& f_T) {
  if (!f_T.allFinite()) return DeviceStatus::kInvalidArgument;
  std::lock_guard lock(mu_);
  f_request_T_ = f_T;
  return StatusLocked();
}

DeviceStatus CanArm::ResetFault() {
  std::lock_guard lock(mu_);
  if (phase_ == Phase::kClosed) return DeviceStatus::kNotOpen;
  reset_requested_ = true;  // sent on the next Tick, from the servo thread
  homing_failed_ = false;   // and the user asks for another homing
  return DeviceStatus::kOk;
}

bool CanArm::Send(const fp::Message& m, fp::Nanoseconds now) { return Send(m, now, config_.send_deadline); }

bool CanArm::Send(const fp::Message& m, fp::Nanoseconds now, fp::Nanoseconds deadline) {
  fp::CanFrame f;
  const fp::EncodeError e = fp::encode(m, f);
  if (e != fp::EncodeError::None) {
    last_error_ = std::string("encode failed: ") + fp::to_string(e);
    ++send_failures_;
    return false;
  }
  const fp::SendStatus s = transport_.send(f, now + deadline);
  if (s != fp::SendStatus::Queued) {
    last_error_ = std::string("transport refused frame: ") + fp::to_string(s);
    ++send_failures_;
    return false;
  }
  return true;
}

void CanArm::HandleFrame(const fp::TimedFrame& rx) {
  fp::Message m;
  const fp::DecodeError e = fp::decode(rx.frame, m);
  if (e != fp::DecodeError::None) {
    decode_errors_.add(e);
    return;
  }
  if (fp::spec_of(fp::kind_of(m)).per_node && fp::node_of(m) != config_.node_id) return;
  const std::int64_t t = Ns(rx.timestamp);

  if (const auto* js = std::get_if<fp::JointState>(&m)) {
    const fp::DecodeError seq = state_sequence_.check(js->counter);
    if (seq != fp::DecodeError::None) {
      decode_errors_.add(seq);
      return;
    }
    const ArmJoints prev = q_;
    q_.yaw_rad = js->position[0];
    q_.pitch_rad = js->position[1];
    q_.insertion_m = js->position[2];
    if (last_state_ns_ >= 0 && t > last_state_ns_) {
      const double dt = 1e-9 * static_cast<double>(t - last_state_ns_);
      const double alpha = 1.0 - std::exp(-2.0 * std::numbers::pi * config_.velocity_filter_hz * dt);
      const Eigen::Vector4d raw = (q_.AsVector() - prev.AsVector()) / dt;
      qd_[0] += alpha * (raw[0] - qd_[0]);
      qd_[1] += alpha * (raw[1] - qd_[1]);
      qd_[3] += alpha * (raw[3] - qd_[3]);
    }
    last_state_ns_ = t;
    node_state_ = js->state;
    node_enabled_ = js->enabled;
    limiter_ = js->limiter;
    link_.OnState(t);
    if (request_sent_ns_ >= 0) {
      round_trip_.Add(t - request_sent_ns_);
      request_sent_ns_ = -1;
    }
  } else if (const auto* aux = std::get_if<fp::AuxState>(&m)) {
    q_.roll_rad = aux->roll_rad;
    jaw_rad_ = aux->jaw_rad;
    buttons_ = (aux->pedal ? 1u : 0u) | (aux->handle_button ? 2u : 0u);
  } else if (const auto* hb = std::get_if<fp::Heartbeat>(&m)) {
    if (hb->state == fp::NodeState::Boot) {  // the boot-up message: a new life of the node
      ForgetNodeSession();
      ++node_boot_count_;
    }
    node_state_ = hb->state;
    node_enabled_ = hb->enabled;
    node_fault_ = hb->latched_fault;
    node_not_homed_ = hb->not_homed;
  } else if (const auto* id = std::get_if<fp::Identity>(&m)) {
    negotiated_ = id->negotiated_minor != 0xFF;
  } else if (const auto* pr = std::get_if<fp::ParameterResponse>(&m)) {
    if (calibration_reader_.Accept(*pr)) {
      if (calibration_reader_.state() == NodeCalibrationReader::State::kInvalid) calibration_read_ns_ = t;
      return;
    }
    if (pr->index == fp::param::kWatchdogTimeout_us && pr->op == fp::ParameterOp::Write) {
      watchdog_configured_ = true;  // an abort is reported, not retried forever
      if (pr->aborted) last_error_ = "node refused watchdog_timeout_us write, abort code " + std::to_string(pr->raw_value);
    }
    // Newest fault-history entry, asked for when a node is seen in Fault without its EMCY.
    const std::uint32_t code = pr->raw_value & 0xFFu;
    if (pr->index == fp::param::kFaultHistory && !pr->aborted && code != 0 && code < fp::kFaultCodeCount &&
        node_state_ == fp::NodeState::Fault)
      node_fault_ = static_cast<fp::FaultCode>(code);
  } else if (const auto* em = std::get_if<fp::Emergency>(&m)) {
    last_emergency_ = em->fault;
    ++emergency_count_;
    node_fault_ = em->fault;  // code None is the fault-reset acknowledgement
    if (em->fault != fp::FaultCode::None) node_enabled_ = false;
  }
}

void CanArm::ForgetNodeSession() {
  state_sequence_.reset();
  calibration_reader_.Restart();  // the node may have booted another slot, or been calibrated
  calibration_read_ns_ = -1;
  negotiated_ = false;
  watchdog_configured_ = config_.node_watchdog_timeout.count() == 0;
  node_enabled_ = false;
  request_sent_ns_ = -1;
  last_handshake_ns_ = -1;
}

void CanArm::SendHandshake(fp::Nanoseconds now) {
  const std::int64_t t = Ns(now);
  // The calibration is read before the node is started (SendCalibrationRead).
  if (negotiated_ && calibration_reader_.state() == NodeCalibrationReader::State::kReading) return;
  // One step of the handshake per retry period: version, NMT start, explicit enable.
  if (last_handshake_ns_ >= 0 && t - last_handshake_ns_ < config_.retry_period.count()) return;
  last_handshake_ns_ = t;
  if (!negotiated_) {
    Send(fp::Hello{config_.node_id, fp::kProtocolMajor, fp::kProtocolMinor}, now);
  } else if (calibration_reader_.state() != NodeCalibrationReader::State::kValid) {
    // Refused: no force from an arm whose offsets, friction and gravity nobody measured. An
    // arm left enabled by an earlier session is disabled.
    if (node_enabled_) Send(fp::Control{config_.node_id, control_counter_++, fp::ControlCommand::Disable}, now);
  } else if (node_not_homed_ && !node_enabled_) {
    // Not homed: positions unknown, the node refuses Enable. Home it (or say why not).
    if (config_.home_at_connection && !homing_failed_) StartHoming();
  } else if (!watchdog_configured_ && !node_enabled_) {
    Send(fp::ParameterRequest{config_.node_id, fp::ParameterOp::Write, fp::ParameterType::U32,
                              fp::param::kWatchdogTimeout_us,
                              static_cast<std::uint32_t>(config_.node_watchdog_timeout.count())},
         now);
  } else if (node_state_ != fp::NodeState::Operational) {
    Send(fp::Nmt{fp::NmtCommand::Start, config_.node_id}, now);
  } else if (!node_enabled_) {
    Send(fp::Control{config_.node_id, control_counter_++, fp::ControlCommand::Enable}, now);
  }
}

bool CanArm::SendCalibrationRead(fp::Nanoseconds now) {
  if (!negotiated_) return false;
  const std::int64_t t = Ns(now);
  if (calibration_reader_.state() == NodeCalibrationReader::State::kInvalid && calibration_read_ns_ >= 0 &&
      t - calibration_read_ns_ >= config_.calibration_recheck.count())
    calibration_reader_.Restart();
  // One read in flight, every other cycle at most: two arms' servo traffic and their reads share
  // one bus within its budget.
  const auto read =
      calibration_reader_.NextRequest(config_.node_id, t, config_.retry_period.count(), kCalibrationReadSpacing_ns);
  // A read is no servo frame: it may wait for a gap in two arms' servo traffic (the lowest
  // priority but one, it loses every arbitration against them) until the next read is due.
  return read && Send(*read, now, fp::Nanoseconds(kCalibrationReadSpacing_ns));
}

void CanArm::SendCommand(fp::Nanoseconds now, bool zero) {
  const std::int64_t t = Ns(now);
  double ramp = 0.0;
  if (!zero) {
    const double on_s = 1e-9 * static_cast<double>(t - enabled_since_ns_);
    ramp = config_.force_ramp_s > 0.0 ? std::clamp(on_s / config_.force_ramp_s, 0.0, 1.0) : 1.0;
  }
  const bool calibrated = calibration_reader_.state() == NodeCalibrationReader::State::kValid;
  const Eigen::Vector3d compensation_A =
      calibrated ? Eigen::Vector3d(calibration_reader_.calibration().CompensationCurrent(q_, qd_))
                 : Eigen::Vector3d::Zero();
  // The motors' torque constants as the reference-load check measured them (protocol 1.3).
  const ArmActuation actuation =
      calibrated ? calibration_reader_.calibration().Corrected(config_.actuation) : config_.actuation;
  last_command_ = TipForceToMotorCurrents(q_, ramp * f_request_T_, actuation, ramp * compensation_A);
  fp::CurrentCommand c{config_.node_id, command_counter_++, fp::CommandMode::MotorCurrent, {}};
  for (int j = 0; j < 3; ++j) c.value[j] = static_cast<float>(last_command_.current_A[j]);
  if (Send(c, now) && request_sent_ns_ < 0) request_sent_ns_ = t;
}

void CanArm::StartHoming() {
  if (homing_thread_.joinable()) return;
  homing_problem_.clear();
  homing_fraction_ = 0.0;
  homing_running_ = true;
  homing_thread_ = std::thread([this] {
    calibration::CalibrationLinkConfig lc;
    lc.node_id = config_.node_id;
    lc.loss_timeout = std::max<fp::Nanoseconds>(config_.loss_timeout, std::chrono::milliseconds(50));
    lc.send_deadline = config_.send_deadline;
    calibration::CalibrationLink::Waiter wait = config_.homing_wait;
    if (!wait) {
      wait = [this](fp::Nanoseconds until) {
        for (fp::Nanoseconds now = transport_.now(); now < until; now = transport_.now())
          std::this_thread::sleep_for(std::min<fp::Nanoseconds>(until - now, std::chrono::microseconds(200)));
      };
    }
    calibration::CalibrationLink link(transport_, wait, lc);
    {
      std::lock_guard lock(homing_link_mu_);
      homing_link_ = &link;
    }
    calibration::HomingPlan plan = config_.homing;
    const auto user_progress = plan.progress;
    plan.progress = [this, user_progress](const std::string& step, double fraction) {
      homing_fraction_ = fraction;
      if (user_progress) user_progress(step, fraction);
    };
    homing_result_ = calibration::HomeArm(link, plan);
    {
      std::lock_guard lock(homing_link_mu_);
      homing_link_ = nullptr;
    }
    homing_running_ = false;
  });
}

bool CanArm::HomingBusy() {
  if (!homing_thread_.joinable()) return false;
  if (homing_running_) return true;
  homing_thread_.join();
  if (homing_result_.homed) {
    ++homing_count_;
  } else {
    homing_failed_ = true;
    homing_problem_ = homing_result_.message;
  }
  node_not_homed_ = !homing_result_.homed;  // until the next heartbeat says so itself
  // The run said Hello and used the node's session: start the handshake afresh. It heard the
  // node all along: the silence of this cycle's link monitor is no lost link.
  ForgetNodeSession();
  node_state_ = fp::NodeState::Boot;
  link_.OnState(transport_.now().count());
  return false;
}

void CanArm::Tick() {
  std::lock_guard lock(mu_);
  if (phase_ == Phase::kClosed) return;
  if (HomingBusy()) return;  // the homing run owns the transport
  const fp::Nanoseconds now = transport_.now();
  const std::int64_t t = Ns(now);
  if (last_tick_ns_ >= 0) loop_period_.Add(t - last_tick_ns_);
  last_tick_ns_ = t;

  fp::TimedFrame rx;
  while (transport_.receive(rx)) HandleFrame(rx);
  fp::BusEvent ev;
  while (transport_.poll_event(ev)) {
    if (ev.kind == fp::BusEvent::Kind::DeviceLost) last_error_ = "transport: device lost";
  }

  if (link_.Poll(t) == LinkMonitor::Event::kLost) {
    // The node may reboot while away: the handshake starts again when it comes back.
    ForgetNodeSession();
    last_state_ns_ = -1;
    qd_.setZero();
  }
  const bool link_ok = link_.up() || !link_.ever_seen();

  if (reset_requested_) {
    reset_requested_ = false;
    Send(fp::Control{config_.node_id, control_counter_++, fp::ControlCommand::FaultReset}, now);
    if (phase_ == Phase::kFault) phase_ = Phase::kConnecting;
    node_fault_ = fp::FaultCode::None;  // until the node says otherwise
    node_state_ = fp::NodeState::Boot;  // unknown until the next report
    last_handshake_ns_ = -1;
  }

  if (node_fault_ != fp::FaultCode::None || node_state_ == fp::NodeState::Fault) {
    phase_ = Phase::kFault;
  } else if (phase_ == Phase::kFault) {
    phase_ = Phase::kConnecting;  // fault cleared (by us or by someone else's reset)
  }
  if (phase_ == Phase::kRunning && !(node_enabled_ && node_state_ == fp::NodeState::Operational)) {
    phase_ = Phase::kConnecting;
  }
  if (phase_ == Phase::kConnecting && node_enabled_ && node_state_ == fp::NodeState::Operational && negotiated_ &&
      watchdog_configured_ && calibration_reader_.state() == NodeCalibrationReader::State::kValid) {
    phase_ = Phase::kRunning;
    enabled_since_ns_ = t;
  }

  if (link_ok && node_state_ == fp::NodeState::Fault && node_fault_ == fp::FaultCode::None &&
      (last_handshake_ns_ < 0 || t - last_handshake_ns_ >= config_.retry_period.count())) {
    // The EMCY was lost (e.g. raised while the link was down): read the node's fault history.
    last_handshake_ns_ = t;
    Send(fp::ParameterRequest{config_.node_id, fp::ParameterOp::Read, fp::ParameterType::U32,
                              fp::param::kFaultHistory, 0},
         now);
  }
  if (!link_ok || phase_ == Phase::kFault) {
    // Stop commanding; SYNC keeps sampling so the return of the node is noticed.
    if (Send(fp::Sync{sync_counter_++}, now) && request_sent_ns_ < 0) request_sent_ns_ = t;
    last_command_ = MotorCurrentCommand{};
    if (phase_ != Phase::kFault) phase_ = Phase::kConnecting;
    return;
  }
  if (phase_ == Phase::kRunning) {
    SendCommand(now, false);
    return;
  }
  // Connecting: handshake, and keep the node sampled (zero commands once it is operational, so
  // the watchdog is fed from the moment the node enables). A cycle that reads the calibration
  // sends that read instead of the sample: the node is not enabled yet, and the bus load stays
  // one frame a cycle.
  SendHandshake(now);
  if (SendCalibrationRead(now)) return;
  if (negotiated_ && node_state_ == fp::NodeState::Operational) {
    SendCommand(now, true);
  } else if (Send(fp::Sync{sync_counter_++}, now) && request_sent_ns_ < 0) {
    request_sent_ns_ = t;
  }
}

JointState CanArm::GetJointState() const {
  std::lock_guard lock(mu_);
  JointState s;
  s.count = 4;
  const Eigen::Vector4d q = q_.AsVector();
  for (int j = 0; j < 4; ++j) {
    s.position[j] = q[j];
    s.velocity[j] = qd_[j];
    s.effort[j] = last_command_.joint_effort[j];
  }
  return s;
}

ToolState CanArm::GetToolState() const {
  std::lock_guard lock(mu_);
  ToolState s;
  const TipPose pose = ForwardKinematics(q_);
  s.p_BTip_B = pose.p_TTip_T;
  s.R_BTip = pose.R_TTip;
  const Eigen::Matrix<double, 6, 4> J = TipJacobian(q_);
  s.v_BTip_B = J.topRows<3>() * qd_;
  s.w_BTip_B = J.bottomRows<3>() * qd_;
  s.gripper_angle_rad = jaw_rad_;
  s.buttons = buttons_;
  s.timestamp_ns = last_state_ns_;
  return s;
}

bool CanArm::calibration_valid() const {
  std::lock_guard lock(mu_);
  return calibration_reader_.state() == NodeCalibrationReader::State::kValid;
}
ArmCalibration CanArm::calibration() const { std::lock_guard lock(mu_); return calibration_reader_.calibration(); }
std::string CanArm::calibration_problem() const { std::lock_guard lock(mu_); return calibration_reader_.problem(); }
ArmJoints CanArm::joints() const { std::lock_guard lock(mu_); return q_; }
std::string CanArm::homing_problem() const { std::lock_guard lock(mu_); return homing_problem_; }
bool CanArm::node_not_homed() const { std::lock_guard lock(mu_); return node_not_homed_; }
std::uint32_t CanArm::homing_count() const { std::lock_guard lock(mu_); return homing_count_; }
calibration::HomingResult CanArm::last_homing() const {
  std::lock_guard lock(mu_);
  return homing_running_ ? calibration::HomingResult{} : homing_result_;
}
fp::NodeState CanArm::node_state() const { std::lock_guard lock(mu_); return node_state_; }
fp::FaultCode CanArm::node_fault() const { std::lock_guard lock(mu_); return node_fault_; }
fp::FaultCode CanArm::last_emergency() const { std::lock_guard lock(mu_); return last_emergency_; }
std::uint32_t CanArm::emergency_count() const { std::lock_guard lock(mu_); return emergency_count_; }
MotorCurrentCommand CanArm::last_command() const { std::lock_guard lock(mu_); return last_command_; }
LatencyStatistics::Summary CanArm::loop_period() const { std::lock_guard lock(mu_); return loop_period_.Summarize(); }
LatencyStatistics::Summary CanArm::round_trip() const { std::lock_guard lock(mu_); return round_trip_.Summarize(); }
void CanArm::ResetStatistics() {
  std::lock_guard lock(mu_);
  loop_period_.Clear();
  round_trip_.Clear();
}
bool CanArm::answered() const { std::lock_guard lock(mu_); return link_.ever_seen(); }
std::uint32_t CanArm::node_boot_count() const { std::lock_guard lock(mu_); return node_boot_count_; }
std::uint32_t CanArm::link_loss_count() const { std::lock_guard lock(mu_); return link_.loss_count(); }
std::uint32_t CanArm::link_restore_count() const { std::lock_guard lock(mu_); return link_.restore_count(); }
fp::DecodeErrorCounters CanArm::decode_errors() const { std::lock_guard lock(mu_); return decode_errors_; }
std::uint64_t CanArm::send_failures() const { std::lock_guard lock(mu_); return send_failures_; }
std::string CanArm::last_error() const { std::lock_guard lock(mu_); return last_error_; }

}  // namespace vesica::device
