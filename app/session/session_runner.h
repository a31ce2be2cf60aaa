#pragma once
// The trainer's three loops (docs/architecture.md, "Threads and rates"), without any GUI:
//   physics thread: samples the input, steps the DissectionSession as fast as it goes (paced to
//     the wall clock in real-time mode), records the input, publishes render snapshots (at most
//     every render_period_s) and haptic contact frames;
//   haptic thread at haptic_rate_hz: renders each instrument's force from the latest contact
//     frame (HapticForceRenderer) at the tool's current point; never waits for physics;
//   the caller's thread (the window's render timer): takes the latest snapshot.
// Data crosses threads only through TripleBuffers, atomics and one short-held mutex.

#include <atomic>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "app/records/session_metrics.h"
#include "app/render/render_frame.h"
#include "app/session/arm_input.h"
#include "app/session/dissection_session.h"
#include "app/session/loop_stats.h"
#include "device/input/input_recorder.h"
#include "device/input/instrument_input_source.h"
#include "physics/scene/triple_buffer.h"

namespace vesica::app {

struct RunnerOptions {
  bool real_time = true;                ///< pace session time to the wall clock (false: as fast as possible)
  double haptic_rate_hz = 1000.0;       ///< > 0
  double render_period_s = 1.0 / 60.0;  ///< snapshot at most this often (wall time)
  double end_after_s = -1;              ///< end the session at this session time (replays); < 0: never
  std::string scenario_name;            ///< written into the input recording
  /// Real haptic devices (arms): the haptic loop reads their tool points and sends them the
  /// rendered force. Null: the force is computed at the physics tool points and only shown.
  std::shared_ptr<HapticIo> haptic_io;
  /// The scenario's Calot's triangle (CalotSessionSetupFor), run in every session; none: no triangle.
  std::optional<CalotSessionSetup> calot;
};

/// What the GUI shows besides the picture; copied out under a short lock.
struct RunnerStatus {
  double session_time_s = 0;  ///< simulated time (steps x h)
  /// Wall-clock time the session has been running (not paused), as the trainee lived it.
  double wall_time_s = 0;
  /// How far the simulation fell behind the wall clock in real-time mode (a slow step, a busy
  /// machine): wall_time_s - session_time_s, >= 0; 0 when not paced to the wall clock.
  double physics_lag_s = 0;
  bool paused = false;
  bool finished = false;  ///< end_after_s reached, End() called, the case ended, or an error stopped physics
  /// The Calot step's critical error (a bile duct injury) ended the case; the trainer shows the debrief.
  bool case_ended = false;
  /// The Calot step's metrics once the session finished (for the debrief); none without a triangle.
  std::optional<calot::CalotMetrics> calot_metrics;
  int session = 0;        ///< which session this status is of: 0 at Start, then the number Reset() returned
  std::string error;      ///< why physics stopped, if it did
  SessionMetrics metrics;
  LoopRate physics, haptic;
  std::array<Eigen::Vector3d, 2> haptic_force_N{Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
};

class SessionRunner {
 public:
  SessionRunner(std::shared_ptr<const physics::DissectionModel> model, const fx::CauteryParams& cautery,
                std::shared_ptr<device::InstrumentInputSource> input, const RunnerOptions& options);
  ~SessionRunner();  ///< stops and joins both threads
  SessionRunner(const SessionRunner&) = delete;
  SessionRunner& operator=(const SessionRunner&) = delete;

  void Start();
  void SetPaused(bool paused);
  /// Starts the session again from the rest state (a fresh DissectionSession, empty recording).
  /// Returns the new session's number (RunnerStatus::session once the physics thread took it).
  int Reset();
  /// Ends the session (the latest one Reset() asked for): physics stops, the metrics are final;
  /// also while paused.
  void End();

  /// The latest render snapshot (caller's thread only; the render loop).
  const RenderFrame& LatestFrame();
  RunnerStatus Status() const;
  /// The input recorded so far (for saving with the session record); physics must be finished
  /// or paused for a consistent copy.
  device::InputRecording Recording() const;

 private:
  void PhysicsLoop();
  void HapticLoop();

  std::shared_ptr<const physics::DissectionModel> model_;
  fx::CauteryParams cautery_;
  std::shared_ptr<device::InstrumentInputSource> input_;
  RunnerOptions options_;

  mutable std::mutex mutex_;  // guards session_ swaps (Reset), status_, recorder_
  std::unique_ptr<DissectionSession> session_;
  device::InputRecorder recorder_;
  RunnerStatus status_;

  physics::TripleBuffer<RenderFrame> frames_;
  std::array<std::unique_ptr<physics::TripleBuffer<physics::HapticContactFrame>>, 2> contact_frames_;
  std::array<std::atomic<double>, 6> tool_tip_{};  // latest commanded tips for the haptic loop
  LoopStats physics_stats_, haptic_stats_;
  std::atomic<bool> stop_{false}, paused_{false};
  std::atomic<int> requested_session_{0}, ended_session_{-1};  // numbers as in RunnerStatus::session
  std::thread physics_thread_, haptic_thread_;
};

}  // namespace vesica::app
