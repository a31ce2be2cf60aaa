#include "app/biopsy/biopsy_runner.h"

#include <chrono>
#include <exception>

namespace vesica::app::biopsy {

BiopsyRunner::BiopsyRunner(std::shared_ptr<const BiopsyPatient> patient, std::shared_ptr<device::StylusDevice> stylus,
                           BiopsySessionSettings settings, double tick_s, std::function<void()> servo)
    : patient_data_(patient),
      stylus_(stylus ? std::move(stylus) : throw std::invalid_argument("biopsy runner: no stylus")),
      tick_s_(tick_s > 0.0 ? tick_s : throw std::invalid_argument("biopsy runner: tick must be > 0")),
      servo_(std::move(servo)),
      session_(std::move(patient), std::move(settings)),
      patient_(session_.patient()),
      placement_(session_.placement()) {
  thread_ = std::thread([this] { HapticLoop(); });
}

BiopsyRunner::~BiopsyRunner() { Stop(); }

void BiopsyRunner::Stop() {
  stop_ = true;
  if (thread_.joinable()) thread_.join();
  stylus_->SetTipForce(Eigen::Vector3d::Zero());
  if (servo_) servo_();  // a UDP stylus sends the zero now
}

SessionMetrics BiopsyRunner::Metrics() { return metrics_.Latest(); }

device::StylusRecording BiopsyRunner::Recording() const {
  const std::lock_guard lock(recording_mutex_);
  return recorder_.recording();
}

std::string BiopsyRunner::error() const {
  const std::lock_guard lock(error_mutex_);
  return error_;
}

void BiopsyRunner::HapticLoop() {
  using Clock = std::chrono::steady_clock;
  const auto period = std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(tick_s_));
  auto next = Clock::now();
  long tick = 0;
  device::StylusState last_good;
  std::uint32_t last_recorded_buttons = 0;
  try {
    while (!stop_) {
      if (servo_) servo_();
      const bool device_ok = stylus_->Status() == device::DeviceStatus::kOk;
      if (device_ok) last_good = stylus_->GetStylusState();
      // Session time counts ticks, so a late tick does not make the patient jump ahead.
      const double t = static_cast<double>(tick) * tick_s_;
      const physics::NeedleForces& forces = session_.Tick(last_good, t);
      // Every 10th tick (10 ms at 1 kHz), and every button change, so a replay takes the sample
      // at the same tick.
      const bool button_changed = last_good.buttons != last_recorded_buttons;
      if (tick % 10 == 0 || button_changed) {
        const std::lock_guard lock(recording_mutex_);
        recorder_.Append(t, last_good);
        last_recorded_buttons = last_good.buttons;
      }
      stylus_->SetTipForce(device_ok ? session_.DeviceForce() : Eigen::Vector3d::Zero());

      NeedleFrame frame;
      frame.time_s = t;
      frame.pose = session_.needle_pose();
      frame.force_W = forces.total_N;
      frame.inside = forces.inside;
      frame.capsule = forces.capsule;
      frame.inserted_m = forces.inserted_m;
      frame.finished = session_.finished();
      frame.insertion_attempts = session_.needle().metrics().insertion_attempts;
      frame.nogo_crossings = session_.needle().metrics().total_no_go_crossings();
      frame.device_ok = device_ok;
      needle_frames_.Publish(frame);
      if (tick % 20 == 0 || frame.finished) metrics_.Publish(session_.Metrics());

      ++tick;
      next += period;
      const auto now = Clock::now();
      // Far behind (a stalled host): go on from now rather than racing through missed ticks.
      if (now - next > 50 * period) next = now;
      std::this_thread::sleep_until(next);
    }
  } catch (const std::exception& e) {
    const std::lock_guard lock(error_mutex_);
    error_ = e.what();
  }
  stylus_->SetTipForce(Eigen::Vector3d::Zero());
}

}  // namespace vesica::app::biopsy
