#pragma once
// A live needle-biopsy session: a haptic thread ticks the BiopsySession at 1 kHz on an absolute
// schedule with the stylus' latest sample and sends the force back to the device; the GUI reads
// what it draws through wait-free triple buffers and never blocks the haptic thread. Breathing
// settings and breath hold go straight to the patient (thread-safe commands).
//
// When the device is not ok (the Omni emulator killed, a cable pulled) the device itself renders
// zero force; the session keeps its last pose and the status says why.

#include <atomic>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include "app/biopsy/biopsy_session.h"
#include "device/stylus/stylus_device.h"
#include "device/stylus/stylus_recorder.h"
#include "physics/scene/triple_buffer.h"

namespace vesica::app::biopsy {

/// What the GUI draws of the needle, from the haptic thread's latest tick.
struct NeedleFrame {
  double time_s = 0.0;
  physics::NeedlePose pose;
  Eigen::Vector3d force_W = Eigen::Vector3d::Zero();  ///< what the trainee feels (world)
  bool inside = false;
  physics::CapsuleContact capsule = physics::CapsuleContact::kNone;
  double inserted_m = 0.0;
  bool finished = false;
  int insertion_attempts = 0;
  int nogo_crossings = 0;
  bool device_ok = false;
};

class BiopsyRunner {
 public:
  /// Starts the haptic thread at once. The device must be open. `servo`, when given, runs first in
  /// every tick (a UDP stylus' Tick: drain its poses, send the last force).
  BiopsyRunner(std::shared_ptr<const BiopsyPatient> patient, std::shared_ptr<device::StylusDevice> stylus,
               BiopsySessionSettings settings = {}, double tick_s = 0.001, std::function<void()> servo = {});
  ~BiopsyRunner();  ///< stops the thread; the device gets zero force
  BiopsyRunner(const BiopsyRunner&) = delete;
  BiopsyRunner& operator=(const BiopsyRunner&) = delete;

  /// Stops the thread and zeroes the device's force (idempotent).
  void Stop();

  // GUI thread:
  [[nodiscard]] const NeedleFrame& LatestNeedle() { return needle_frames_.Latest(); }
  [[nodiscard]] const physics::PatientSnapshot& LatestPatient() { return patient_.render_snapshots().Latest(); }
  [[nodiscard]] const BiopsyPatient& patient_data() const { return *patient_data_; }
  [[nodiscard]] const StylusPlacement& placement() const { return placement_; }
  [[nodiscard]] device::StylusDevice& stylus() { return *stylus_; }
  void SetRespiration(const physics::RespirationSettings& settings) { patient_.SetRespiration(settings); }
  void HoldBreath() { patient_.HoldBreath(); }
  void ResumeBreathing() { patient_.ResumeBreathing(); }
  /// The metrics so far (from the last tick); final once finished.
  [[nodiscard]] SessionMetrics Metrics();
  /// The stylus stream so far, a sample every record_period_s of session time (what the session
  /// ticked with): a stylus recording that replays the session (vesica-replay).
  [[nodiscard]] device::StylusRecording Recording() const;
  /// The haptic thread stopped on an error (a bad sample it could not use); empty if none.
  [[nodiscard]] std::string error() const;

 private:
  void HapticLoop();

  std::shared_ptr<const BiopsyPatient> patient_data_;
  std::shared_ptr<device::StylusDevice> stylus_;
  double tick_s_;
  std::function<void()> servo_;
  BiopsySession session_;
  physics::BreathingPatient& patient_;
  StylusPlacement placement_;
  physics::TripleBuffer<NeedleFrame> needle_frames_{NeedleFrame{}};
  physics::TripleBuffer<SessionMetrics> metrics_{SessionMetrics{}};
  mutable std::mutex recording_mutex_;
  device::StylusRecorder recorder_;  // guarded by recording_mutex_
  mutable std::mutex error_mutex_;
  std::string error_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

}  // namespace vesica::app::biopsy
