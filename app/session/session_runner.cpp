#include "app/session/session_runner.h"

#include <algorithm>
#include <chrono>
#include <exception>

#include "physics/scene/haptic_force_renderer.h"

namespace vesica::app {

namespace {
using Clock = std::chrono::steady_clock;
double Seconds(Clock::duration d) { return std::chrono::duration<double>(d).count(); }
}  // namespace

SessionRunner::SessionRunner(std::shared_ptr<const physics::DissectionModel> model, const fx::CauteryParams& cautery,
                             std::shared_ptr<device::InstrumentInputSource> input, const RunnerOptions& options)
    : model_(std::move(model)),
      cautery_(cautery),
      input_(std::move(input)),
      options_(options),
      session_(std::make_unique<DissectionSession>(model_, cautery_, options_.calot)),
      recorder_(options.scenario_name),
      frames_(session_->MakeRenderFrame()) {
  for (auto& c : contact_frames_)
    c = std::make_unique<physics::TripleBuffer<physics::HapticContactFrame>>(physics::HapticContactFrame{});
  status_.metrics = session_->metrics();
}

SessionRunner::~SessionRunner() {
  stop_ = true;
  if (physics_thread_.joinable()) physics_thread_.join();
  if (haptic_thread_.joinable()) haptic_thread_.join();
}

void SessionRunner::Start() {
  if (physics_thread_.joinable()) return;
  physics_thread_ = std::thread([this] { PhysicsLoop(); });
  haptic_thread_ = std::thread([this] { HapticLoop(); });
}

void SessionRunner::SetPaused(bool paused) { paused_ = paused; }
int SessionRunner::Reset() { return ++requested_session_; }
void SessionRunner::End() { ended_session_ = requested_session_.load(); }

const RenderFrame& SessionRunner::LatestFrame() { return frames_.Latest(); }

RunnerStatus SessionRunner::Status() const {
  std::lock_guard lock(mutex_);
  RunnerStatus s = status_;
  s.paused = paused_;
  s.physics = physics_stats_.Snapshot();
  s.haptic = haptic_stats_.Snapshot();
  return s;
}

device::InputRecording SessionRunner::Recording() const {
  std::lock_guard lock(mutex_);
  return recorder_.recording();
}

void SessionRunner::PhysicsLoop() {
  Clock::time_point wall_start = Clock::now(), last_publish = Clock::time_point{};
  double paced_from_s = 0;  // session time at wall_start
  double wall_before_s = 0;  // running wall time of the session before wall_start (pauses excluded)
  bool finished = false, idle = false;
  int session = 0;
  while (!stop_) {
    if (const int wanted = requested_session_.load(); wanted != session) {
      std::lock_guard lock(mutex_);
      session_ = std::make_unique<DissectionSession>(model_, cautery_, options_.calot);
      recorder_ = device::InputRecorder(options_.scenario_name);
      status_ = RunnerStatus{};
      status_.session = session = wanted;
      finished = false;
      wall_start = Clock::now();
      paced_from_s = 0;
      wall_before_s = 0;
    }
    const bool end_asked = ended_session_.load() == session;
    if (!finished && paused_ && end_asked) {  // End while paused: the session ends where it stands
      std::lock_guard lock(mutex_);
      finished = status_.finished = true;
    }
    if (finished || paused_) {
      if (!idle) wall_before_s += Seconds(Clock::now() - wall_start);  // the pause does not count
      idle = true;
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
      wall_start = Clock::now();
      paced_from_s = session_->time_s();
      continue;
    }
    idle = false;
    // Session time as steps x h (not a running sum), as RunReplay samples: same input, same state.
    const double t = static_cast<double>(session_->scene().steps()) * model_->settings.time_step_s;
    if (options_.real_time) {
      const double ahead_s = (t - paced_from_s) - Seconds(Clock::now() - wall_start);
      if (ahead_s > 0) {
        std::this_thread::sleep_for(std::chrono::duration<double>(ahead_s));
      } else if (ahead_s < -0.05) {
        // Fell behind (a slow step, the machine busy): go on from now rather than race to catch
        // up, which would play the lost time back fast. The session's wall time goes on; the
        // lag is reported (status, records), never hidden in a slower session clock.
        wall_before_s += Seconds(Clock::now() - wall_start);
        wall_start = Clock::now();
        paced_from_s = t;
      }
    }
    std::string error;
    try {
      const device::InputFrame in = input_->Sample(t);
      const SessionStepReport r = session_->Step(in);
      device::InputFrame stamped = in;
      stamped.time_s = t;
      physics_stats_.Tick(Clock::now());
      for (int i = 0; i < 2; ++i) {
        contact_frames_[static_cast<size_t>(i)]->Publish(session_->scene().haptic_frame(i));
        const Eigen::Vector3d tip = session_->scene().tool_tip(i);
        for (int k = 0; k < 3; ++k) tool_tip_[static_cast<size_t>(3 * i + k)].store(tip[k], std::memory_order_relaxed);
      }
      const bool ended = end_asked || session_->case_ended() ||
                         (options_.end_after_s >= 0 && session_->time_s() >= options_.end_after_s);
      const Clock::time_point now = Clock::now();
      if (ended || Seconds(now - last_publish) >= options_.render_period_s) {
        frames_.Publish(session_->MakeRenderFrame());
        last_publish = now;
      }
      std::lock_guard lock(mutex_);
      recorder_.Append(stamped);
      status_.session_time_s = session_->time_s();
      if (options_.real_time) {
        status_.wall_time_s = wall_before_s + Seconds(now - wall_start);
        status_.physics_lag_s = std::max(0.0, status_.wall_time_s - status_.session_time_s);
      } else {
        status_.wall_time_s = status_.session_time_s;  // as fast as it goes: only simulated time means anything
      }
      status_.metrics = session_->metrics();
      (void)r;
      if (ended) {
        finished = status_.finished = true;
        status_.case_ended = session_->case_ended();
        if (const calot::CalotMetrics* calot = session_->calot_metrics()) status_.calot_metrics = *calot;
      }
    } catch (const std::exception& e) {
      std::lock_guard lock(mutex_);
      status_.error = e.what();
      finished = status_.finished = true;
    }
  }
}

void SessionRunner::HapticLoop() {
  const double period_s = 1.0 / options_.haptic_rate_hz;
  const double blend_s = model_->settings.time_step_s;
  std::array<physics::HapticForceRenderer, 2> renderers{physics::HapticForceRenderer(blend_s),
                                                        physics::HapticForceRenderer(blend_s)};
  std::array<double, 2> last_frame_time{-1, -1};
  const Clock::time_point start = Clock::now();
  Clock::time_point next = start;
  while (!stop_) {
    const double t = Seconds(Clock::now() - start);
    std::array<Eigen::Vector3d, 2> force;
    HapticIo* io = options_.haptic_io.get();
    if (io != nullptr) io->ServoTick();
    for (size_t i = 0; i < 2; ++i) {
      Eigen::Vector3d p(tool_tip_[3 * i].load(std::memory_order_relaxed),
                        tool_tip_[3 * i + 1].load(std::memory_order_relaxed),
                        tool_tip_[3 * i + 2].load(std::memory_order_relaxed));
      if (io != nullptr) io->ToolPoint(static_cast<int>(i), p);  // the hand's measured point when there is one
      const physics::HapticContactFrame& frame = contact_frames_[i]->Latest();
      if (frame.time_s != last_frame_time[i]) {
        renderers[i].Update(frame, p, t);
        last_frame_time[i] = frame.time_s;
      }
      force[i] = renderers[i].Force(p, t);
      if (io != nullptr) io->SetForce(static_cast<int>(i), force[i]);
    }
    haptic_stats_.Tick(Clock::now());
    {
      std::lock_guard lock(mutex_);
      status_.haptic_force_N = force;
    }
    next += std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(period_s));
    std::this_thread::sleep_until(next);
  }
}

}  // namespace vesica::app
