// Compiled only when CMake found OpenHaptics (device/stylus/CMakeLists.txt).
#include "device/stylus/openhaptics_stylus.h"

#include <HD/hd.h>

#include <algorithm>
#include <chrono>

#include "device/stylus/stylus_force.h"

namespace vesica::device {
namespace {

std::int64_t SteadyNowNs() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

// The HD API works in mm; we in m.
constexpr double kMetresPerMm = 1e-3;

std::string HdErrorText(const HDErrorInfo& error) {
  const char* text = hdGetErrorString(error.errorCode);
  return std::string("HD error ") + std::to_string(error.errorCode) + " (" + (text ? text : "?") + "), internal " +
         std::to_string(error.internalErrorCode);
}

HDCallbackCode HDCALLBACK ServoTrampoline(void* user) {
  static_cast<OpenHapticsStylus*>(user)->ServoCallback();
  return HD_CALLBACK_CONTINUE;  // stays scheduled: a loss is detected, not ended, here
}

}  // namespace

struct OpenHapticsStylus::Hd {
  HHD device = HD_INVALID_HANDLE;
  HDSchedulerHandle callback = 0;
  bool scheduler_started = false;
};

OpenHapticsStylus::OpenHapticsStylus(OpenHapticsStylusConfig config)
    : config_(std::move(config)),
      capabilities_(PhantomOmniCapabilities()),
      hd_(std::make_unique<Hd>()),
      link_(config_.loss_timeout_ns) {}

OpenHapticsStylus::~OpenHapticsStylus() { Close(); }

DeviceStatus OpenHapticsStylus::Open() {
  {
    std::lock_guard lock(mu_);
    if (open_) return DeviceStatus::kAlreadyOpen;
  }
  const HHD device = hdInitDevice(config_.device_name.empty() ? HD_DEFAULT_DEVICE : config_.device_name.c_str());
  HDErrorInfo error = hdGetError();
  if (HD_DEVICE_ERROR(error)) {
    std::lock_guard lock(mu_);
    error_text_ = "hdInitDevice: " + HdErrorText(error);
    return DeviceStatus::kNoResponse;
  }
  hdMakeCurrentDevice(device);
  HDdouble max_force_N = 0;
  hdGetDoublev(HD_NOMINAL_MAX_FORCE, &max_force_N);
  HDdouble continuous_N = 0;
  hdGetDoublev(HD_NOMINAL_MAX_CONTINUOUS_FORCE, &continuous_N);
  const char* model = hdGetString(HD_DEVICE_MODEL_TYPE);
  {
    std::lock_guard lock(mu_);
    if (max_force_N > 0) capabilities_.device.max_force_N = max_force_N;
    if (continuous_N > 0) capabilities_.max_continuous_force_N = continuous_N;
    if (model) capabilities_.device.model_name = model;
    link_ = LinkMonitor(config_.loss_timeout_ns);
    requested_force_.setZero();
    error_text_.clear();
    open_ = true;
  }
  hdEnable(HD_FORCE_OUTPUT);
  hd_->device = device;
  hd_->callback = hdScheduleAsynchronous(ServoTrampoline, this, HD_MAX_SCHEDULER_PRIORITY);
  hdStartScheduler();
  error = hdGetError();
  if (HD_DEVICE_ERROR(error)) {
    const std::string why = "hdStartScheduler: " + HdErrorText(error);
    Close();
    std::lock_guard lock(mu_);
    error_text_ = why;
    return DeviceStatus::kTransportError;
  }
  hd_->scheduler_started = true;
  return DeviceStatus::kConnecting;  // kOk from the first servo callback on
}

void OpenHapticsStylus::Close() {
  {
    std::lock_guard lock(mu_);
    if (!open_) return;
    requested_force_.setZero();  // the last callbacks before the stop write zero
    open_ = false;
  }
  if (hd_->scheduler_started) hdStopScheduler();
  if (hd_->callback != 0) hdUnschedule(hd_->callback);
  if (hd_->device != HD_INVALID_HANDLE) {
    hdDisable(HD_FORCE_OUTPUT);
    hdDisableDevice(hd_->device);
  }
  *hd_ = Hd{};
}

void OpenHapticsStylus::ServoCallback() {
  const std::int64_t now_ns = SteadyNowNs();
  hdBeginFrame(hd_->device);
  HDdouble transform[16];  // column major, mm
  hdGetDoublev(HD_CURRENT_TRANSFORM, transform);
  HDint buttons = 0;
  hdGetIntegerv(HD_CURRENT_BUTTONS, &buttons);
  HDdouble force[3] = {0, 0, 0};
  {
    std::lock_guard lock(mu_);
    const bool up = open_ && link_.up() && error_text_.empty();
    const double ramp =
        config_.force_ramp_s <= 0
            ? 1.0
            : std::clamp(1e-9 * static_cast<double>(now_ns - ramp_start_ns_) / config_.force_ramp_s, 0.0, 1.0);
    rendered_force_ = up ? Eigen::Vector3d(ramp * requested_force_) : Eigen::Vector3d::Zero();
    for (int i = 0; i < 3; ++i) force[i] = rendered_force_[i];
  }
  hdSetDoublev(HD_CURRENT_FORCE, force);
  hdEndFrame(hd_->device);
  const HDErrorInfo error = hdGetError();

  std::lock_guard lock(mu_);
  if (HD_DEVICE_ERROR(error)) {
    // Communication or force errors (cable pulled, amplifiers off, over-temperature): force off
    // until the user resets; the callback keeps running so the state shows when it comes back.
    error_text_ = HdErrorText(error);
    requested_force_.setZero();
    return;
  }
  StylusState s;
  s.p_BTip_B = kMetresPerMm * Eigen::Vector3d(transform[12], transform[13], transform[14]);
  // The stylus points along the end effector's -z (at the home pose, into the workspace, away
  // from the user): D is minus the third column of the rotation.
  s.d_B = -Eigen::Vector3d(transform[8], transform[9], transform[10]).normalized();
  s.buttons =
      ((buttons & HD_DEVICE_BUTTON_1) ? kStylusButton1 : 0u) | ((buttons & HD_DEVICE_BUTTON_2) ? kStylusButton2 : 0u);
  s.timestamp_ns = now_ns;
  if (StylusStateProblem(s)) return;  // never expected from the driver; keep the last good pose
  const bool was_up = link_.up();
  link_.OnState(now_ns);
  if (!was_up) {
    ramp_start_ns_ = now_ns;
    requested_force_.setZero();
  }
  state_ = s;
}

void OpenHapticsStylus::Poll() {
  std::lock_guard lock(mu_);
  if (link_.Poll(SteadyNowNs()) == LinkMonitor::Event::kLost) requested_force_.setZero();
}

DeviceStatus OpenHapticsStylus::Status() const {
  std::lock_guard lock(mu_);
  if (!open_) return error_text_.empty() ? DeviceStatus::kNotOpen : DeviceStatus::kNoResponse;
  if (!error_text_.empty()) return DeviceStatus::kLinkLost;
  if (!link_.ever_seen()) return DeviceStatus::kConnecting;
  return link_.up() ? DeviceStatus::kOk : DeviceStatus::kLinkLost;
}

std::string OpenHapticsStylus::StatusText() const {
  const DeviceStatus status = Status();
  std::lock_guard lock(mu_);
  std::string text = capabilities_.device.model_name + " (OpenHaptics): " + std::string(ToString(status));
  if (!error_text_.empty())
    text += ": " + error_text_ + ", force off";
  else if (status == DeviceStatus::kLinkLost)
    text += ": the servo loop stopped, force off";
  return text;
}

StylusState OpenHapticsStylus::GetStylusState() const {
  std::lock_guard lock(mu_);
  return state_;
}

DeviceStatus OpenHapticsStylus::SetTipForce(const Eigen::Vector3d& f_B) {
  if (ForceProblem(f_B)) return DeviceStatus::kInvalidArgument;
  const DeviceStatus status = Status();
  if (status != DeviceStatus::kOk) return status;
  std::lock_guard lock(mu_);
  requested_force_ = SaturateForce(f_B, capabilities_.device.max_force_N);
  return DeviceStatus::kOk;
}

Eigen::Vector3d OpenHapticsStylus::RenderedForce() const {
  std::lock_guard lock(mu_);
  return rendered_force_;
}

DeviceStatus OpenHapticsStylus::ResetFault() {
  {
    std::lock_guard lock(mu_);
    error_text_.clear();
    requested_force_.setZero();
    ramp_start_ns_ = SteadyNowNs();
  }
  return Status();
}

}  // namespace vesica::device
