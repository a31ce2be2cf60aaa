// The guided hand steps: the motors stay off while a person moves the roll, the jaw handle or the
// pedal as prompted; the node reports the raw sensors (protocol 1.2) and the guide shows them
// live until the person accepts. Each period also feeds the node's session watchdog.
#include <cmath>
#include <cstdlib>
#include <numbers>
#include <string>
#include <vector>

#include "device/calibration/calibration_abort.h"
#include "device/calibration/calibration_step.h"

namespace vesica::device::calibration {
namespace {

constexpr int kRoll = 0, kJaw = 1, kPedal = 2;

struct Guided {
  const char* step;
  int sensor;
  std::vector<const char*> instructions;
  /// "" when the readings (one per instruction) are acceptable, else why not.
  std::string (*check)(const CalibrationPlan& plan, const std::vector<std::int32_t>& readings);
};

// One prompt until the guide answers; the motors get no current meanwhile.
HandReply Prompt(StepContext& ctx, const HandPromptSpec& spec, int sensor, std::int32_t& value) {
  const double until = ctx.link.now_s() + ctx.plan.hand_prompt_timeout_s;
  while (true) {
    ctx.link.Cycle({0.0, 0.0, 0.0});
    const HandReply reply = ctx.plan.hand_guide(spec, static_cast<double>(ctx.link.hand_raw(sensor)));
    if (reply == HandReply::kAccept) value = ctx.link.hand_raw(sensor);
    if (reply != HandReply::kWait) return reply;
    if (ctx.link.now_s() > until)
      throw CalibrationAbort(AbortReason::kMeasurement, spec.step + ": no answer to the prompt");
  }
}

// The step's prompts, again on a retry or a failed check; the accepted readings.
std::vector<std::int32_t> RunGuided(StepContext& ctx, const Guided& g, int& attempts) {
  if (!ctx.plan.hand_guide)
    throw CalibrationAbort(AbortReason::kMeasurement,
                           std::string(g.step) + ": needs a person to move the hand at an interactive tool");
  for (int j = 0; j < 3; ++j) ctx.servo.Off(j);
  ctx.link.StartHandSensorReadout("the guided hand steps");
  ctx.Progress(g.step, 0.0);
  std::string reason;
  int refused = 0;
  for (int attempt = 1;; ++attempt) {
    std::vector<std::int32_t> readings;
    bool retry = false;
    for (std::size_t i = 0; i < g.instructions.size() && !retry; ++i) {
      HandPromptSpec spec{
          g.step, g.instructions[i], static_cast<int>(i), static_cast<int>(g.instructions.size()), attempt, reason};
      std::int32_t value = 0;
      switch (Prompt(ctx, spec, g.sensor, value)) {
        case HandReply::kAccept:
          readings.push_back(value);
          break;
        case HandReply::kRetry:
          retry = true;
          reason = "retry asked for";
          break;
        case HandReply::kAbort:
          throw CalibrationAbort(AbortReason::kAbortRequested, std::string(g.step) +
                                                                   ": stopped at the prompt; the stored calibration "
                                                                   "is in force");
        case HandReply::kWait:
          break;
      }
      ctx.Progress(g.step, static_cast<double>(i + 1) / static_cast<double>(g.instructions.size() + 1));
    }
    if (retry) continue;
    reason = g.check ? g.check(ctx.plan, readings) : "";
    if (reason.empty()) {
      attempts = attempt;
      ctx.Progress(g.step, 1.0);
      return readings;
    }
    if (++refused >= ctx.plan.hand_attempts)
      throw CalibrationAbort(AbortReason::kMeasurement, std::string(g.step) + ": " + reason + " (refused after " +
                                                            std::to_string(refused) + " tries)");
  }
}

std::string CheckJaw(const CalibrationPlan& plan, const std::vector<std::int32_t>& r) {
  const int span = std::abs(r[1] - r[0]);
  if (span >= plan.jaw_min_span_counts) return "";
  return "the jaw handle moved its sensor only " + std::to_string(span) + " counts between closed and open (at least " +
         std::to_string(static_cast<int>(plan.jaw_min_span_counts)) + ")";
}

std::string CheckPedal(const CalibrationPlan& plan, const std::vector<std::int32_t>& r) {
  const int travel = std::abs(r[1] - r[0]);
  if (travel >= plan.pedal_min_travel_counts) return "";
  return "the pedal has no travel: " + std::to_string(travel) + " counts between released and pressed (at least " +
         std::to_string(static_cast<int>(plan.pedal_min_travel_counts)) + ")";
}

}  // namespace

void CalibrateRollOffset(StepContext& ctx) {
  const Guided g{
      "roll offset", kRoll, {"Turn the instrument until its roll mark is at the top and hold it there."}, nullptr};
  HandSensorCalibration& h = ctx.result.hand;
  const std::int32_t raw = RunGuided(ctx, g, h.roll_attempts)[0];
  double offset = raw * 2.0 * std::numbers::pi / 16384.0;
  if (offset > std::numbers::pi) offset -= 2.0 * std::numbers::pi;
  h.roll_raw = raw;
  h.roll_offset_rad = offset;
  h.roll_measured = true;
}

void CalibrateJawSpan(StepContext& ctx) {
  const Guided g{"jaw span",
                 kJaw,
                 {"Close the jaw handle fully and hold it there.", "Open the jaw handle fully and hold it there."},
                 CheckJaw};
  HandSensorCalibration& h = ctx.result.hand;
  const auto r = RunGuided(ctx, g, h.jaw_attempts);
  h.jaw_closed_raw = r[0];
  h.jaw_open_raw = r[1];
  h.jaw_measured = true;
}

void CalibratePedalTravel(StepContext& ctx) {
  const Guided g{"pedal travel",
                 kPedal,
                 {"Take your foot off the pedal.", "Press the pedal down to its stop and hold it there."},
                 CheckPedal};
  HandSensorCalibration& h = ctx.result.hand;
  const auto r = RunGuided(ctx, g, h.pedal_attempts);
  h.pedal_up_raw = r[0];
  h.pedal_down_raw = r[1];
  h.pedal_measured = true;
}

void CalibrateHandSensors(StepContext& ctx) {
  CalibrateRollOffset(ctx);
  CalibrateJawSpan(ctx);
  CalibratePedalTravel(ctx);
}

}  // namespace vesica::device::calibration
