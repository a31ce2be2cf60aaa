#pragma once
// Runs a recorded input session through a dissection session at the physics rate: step k uses
// the recording sampled at its start time + k h, until the recording ends. Optional callback per
// step (the PNG writer, progress). No display needed.

#include <functional>
#include <vector>

#include "app/session/dissection_session.h"
#include "device/input/replay_input.h"

namespace vesica::app {

struct ReplayOutcome {
  long steps = 0;
  bool finite = true;                 ///< every state stayed finite (else the run stopped there)
  double max_energy_J = 0;            ///< largest DissectionScene::Energy() seen
  long rejected_fem_steps = 0;        ///< gallbladder steps rolled back by the divergence guard
  double gallbladder_free_at_s = -1;  ///< session time the last spring was cut, -1 if never
  /// Wall time of each session step (the step alone: not the checks above, not the callback),
  /// to tell whether the scene keeps up with real time on this machine.
  std::vector<double> step_wall_ms;
};

/// The longest recording a replay runs: 12 hours of session time (a session is minutes long).
inline constexpr double kMaxReplayDuration_s = 12.0 * 3600.0;

/// Steps of `time_step_s` that replay a recording spanning `duration_s`: floor(duration / h) + 1.
/// Throws std::out_of_range, naming the span and the limit, for a span that is not finite, negative
/// or longer than kMaxReplayDuration_s (a last row at 1e308 s once gave 0 steps and a success).
long ReplayStepCount(double duration_s, double time_step_s);

using ReplayStepCallback = std::function<void(const DissectionSession&, const SessionStepReport&)>;

/// Throws std::out_of_range as ReplayStepCount does, before the first step.
ReplayOutcome RunReplay(DissectionSession& session, device::ReplayInput& input, const ReplayStepCallback& on_step = {});

}  // namespace vesica::app
