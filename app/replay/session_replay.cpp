#include "app/replay/session_replay.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>

namespace vesica::app {

namespace {

/// Shortest round-trip text: the refused span shows every digit it has.
std::string Shortest(double v) {
  std::array<char, 32> buf{};
  return std::string(buf.data(), std::to_chars(buf.data(), buf.data() + buf.size(), v).ptr);
}

}  // namespace

long ReplayStepCount(double duration_s, double time_step_s) {
  if (!(duration_s >= 0 && duration_s <= kMaxReplayDuration_s))
    throw std::out_of_range("the recording spans " + Shortest(duration_s) + " s, more than a replay runs (at most " +
                            Shortest(kMaxReplayDuration_s) + " s, " +
                            std::to_string(static_cast<long>(kMaxReplayDuration_s / time_step_s) + 1) + " steps of " +
                            Shortest(time_step_s) + " s)");
  return static_cast<long>(std::floor(duration_s / time_step_s + 1e-9)) + 1;
}

ReplayOutcome RunReplay(DissectionSession& session, device::ReplayInput& input, const ReplayStepCallback& on_step) {
  ReplayOutcome out;
  const double h = session.scene().model().settings.time_step_s;
  const long steps = ReplayStepCount(input.duration_s(), h);
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
