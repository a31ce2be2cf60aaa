// home: find an arm's frame again after power-up (protocol 1.4). The arm moves: each joint seeks
// its lower hard stop, then creeps to its reference index; nothing is written to its flash.
#include <cstdio>

#include "app/calibrate/acceptance.h"
#include "app/calibrate/commands.h"
#include "app/calibrate/exit_codes.h"
#include "app/calibrate/open_arm.h"
#include "device/calibration/homing.h"

namespace vesica::app::calibrate {

namespace cal = device::calibration;
using nlohmann::json;

namespace {

std::string Signed(double v, const char* format) {
  char b[32];
  std::snprintf(b, sizeof b, format, v);
  return b;
}

}  // namespace

CommandOutcome Home(ToolSession& s, int arm, const HomeRequest& request) {
  OpenedArm a;
  CommandOutcome failure;
  if (!OpenArm(s, arm, &a, &failure)) return failure;
  const std::uint8_t minor = a.link->negotiated_minor();
  if (minor == 0xFF || minor < fp::kHomingMinor)
    return ToolSession::Failure(kExitProtocolTooOld,
                                a.text + " speaks protocol 1." + std::to_string(minor == 0xFF ? 0 : minor) +
                                    ": homing needs 1." + std::to_string(fp::kHomingMinor) +
                                    " (update the arm's firmware); its positions are right only if it powered up "
                                    "where it was calibrated; nothing moved",
                                {{"arm", arm}, {"protocol_negotiated_minor", minor}});
  if (a.info.active_slot < 0)
    return ToolSession::Failure(kExitFailed,
                                a.text +
                                    " has no stored calibration to home to (its index positions and range are "
                                    "not known); run `vesica-calibrate calibrate " +
                                    std::to_string(arm) + "` (nothing moved)",
                                {{"arm", arm}});
  MotionNotice notice;
  notice.arm = arm;
  notice.arm_text = a.text;
  notice.max_current_A = request.max_current_A;
  std::string joints;
  for (int j = 0; j < 3; ++j)
    if ((request.joints >> j) & 1u) joints += std::string(joints.empty() ? "" : ", ") + JointName(j);
  notice.motions.push_back(
      "homing: each joint seeks its lower hard stop slowly, then creeps to its encoder's "
      "reference index, then returns to the centre (" +
      joints + ")");
  if (!s.ui().ConfirmMotion(notice))
    return ToolSession::Failure(kExitAborted, "arm " + std::to_string(arm) + ": not confirmed; nothing moved",
                                {{"arm", arm}});
  cal::HomingPlan plan;
  plan.joints = static_cast<std::uint8_t>(request.joints);
  plan.session_max_current_A = request.max_current_A;
  plan.progress = [&s, arm](const std::string& step, double f) { s.Progress(arm, step, f); };
  const cal::HomingResult r = cal::HomeArm(*a.link, plan);
  json joints_json = json::array();
  std::string lines;
  for (int j = 0; j < 3; ++j) {
    if (!((request.joints >> j) & 1u)) continue;
    const bool rotary = j < 2;
    joints_json.push_back({{"joint", JointName(j)},
                           {"offset_before", r.offset_before[j]},
                           {"offset_after", r.offset_after[j]},
                           {"correction", r.correction[j]},
                           {"unit", rotary ? "rad" : "m"}});
    lines += std::string("  ") + JointName(j) + std::string(10 - std::string(JointName(j)).size(), ' ') + "moved " +
             Signed(r.correction[j], rotary ? "%+.5f rad" : "%+.5f m") + " while off (offset " +
             Signed(r.offset_before[j], "%+.5f") + " -> " + Signed(r.offset_after[j], "%+.5f") + ")\n";
  }
  if (!r.homed) {
    const int code = ExitCodeOf(r.abort, "home");
    CommandOutcome o = ToolSession::Failure(
        code, "arm " + std::to_string(arm) + ": " + r.message + "; the arm is disabled and not homed", {{"arm", arm}});
    o.json["command"] = "home";
    o.json["error"]["reason"] = cal::ToString(r.abort);
    o.json["error"]["step"] = "home";
    o.json["homed"] = false;
    return o;
  }
  CommandOutcome o;
  o.json = {
      {"command", "home"},          {"ok", true},           {"arm", arm}, {"homed", true}, {"was_homed", r.was_homed},
      {"bus_time_s", r.bus_time_s}, {"joints", joints_json}};
  o.text = a.text + ": homed, " + Signed(r.bus_time_s, "%.1f") + " s of bus time\n" + lines;
  return o;
}

}  // namespace vesica::app::calibrate
