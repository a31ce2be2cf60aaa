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

using ReplayStepCallback = std::function<void(const DissectionSession&, const SessionStepReport&)>;

ReplayOutcome RunReplay(DissectionSession& session, device::ReplayInput& input, const ReplayStepCallback& on_step = {});

}  // namespace vesica::app
