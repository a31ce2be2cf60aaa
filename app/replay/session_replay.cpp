#include "app/replay/session_replay.h"

#include <algorithm>
#include <chrono>
#include <cmath>

namespace vesica::app {

ReplayOutcome RunReplay(DissectionSession& session, device::ReplayInput& input, const ReplayStepCallback& on_step) {
  ReplayOutcome out;
  const double h = session.scene().model().settings.time_step_s;
  const long steps = static_cast<long>(std::floor(input.duration_s() / h + 1e-9)) + 1;
  for (long k = 0; k < steps; ++k) {
    const device::InputFrame in = input.Sample(input.start_time_s() + static_cast<double>(k) * h);
    const auto began = std::chrono::steady_clock::now();
    const SessionStepReport r = session.Step(in);
    out.step_wall_ms.push_back(
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - began).count());
    ++out.steps;
    if (!r.physics.gallbladder_accepted) ++out.rejected_fem_steps;
    const double energy = session.scene().Energy();
    out.finite = std::isfinite(energy) && session.scene().gallbladder().state().displacement_m.allFinite() &&
                 session.scene().liver_positions().allFinite();
    if (!out.finite) break;
    out.max_energy_J = std::max(out.max_energy_J, energy);
    if (out.gallbladder_free_at_s < 0 && session.gallbladder_free()) out.gallbladder_free_at_s = session.time_s();
    if (on_step) on_step(session, r);
  }
  return out;
}

}  // namespace vesica::app
