// scan and info: what is on the bus, read only (nothing moves, nothing is written to an arm).
#include "app/calibrate/commands.h"
#include "app/calibrate/exit_codes.h"
#include "app/calibrate/json_views.h"
#include "app/calibrate/open_arm.h"
#include "app/calibrate/stored_calibration.h"
#include "device/calibration/calibration_abort.h"

namespace vesica::app::calibrate {

namespace cal = device::calibration;
using nlohmann::json;

namespace {

std::string InfoText(const OpenedArm& a, const NodeHeartbeat* hb) {
  std::string s = a.text + ": " + StateText(hb) + "\n";
  // The core's description, indented under the arm.
  std::string d = a.info.Describe();
  std::size_t start = 0;
  while (start < d.size()) {
    const std::size_t end = d.find('\n', start);
    s += "  " + d.substr(start, end - start) + "\n";
    if (end == std::string::npos) break;
    start = end + 1;
  }
  return s;
}

}  // namespace

CommandOutcome Scan(ToolSession& s) {
  CommandOutcome o;
  json arms = json::array();
  int found = 0, too_old = 0;
  o.text = "bus: " + Describe(s.options().bus) + "\n";
  for (int arm = 1; arm <= 2; ++arm) {
    OpenedArm a;
    CommandOutcome failure;
    if (OpenArm(s, arm, &a, &failure)) {
      ++found;
      const NodeHeartbeat* hb = s.ObserverOf(arm)->heartbeat(arm);
      json j = ToJson(a.info, hb);
      j["arm"] = arm;
      j["found"] = true;
      arms.push_back(j);
      o.text += InfoText(a, hb);
      continue;
    }
    // Ctrl-C ends the scan; an arm that fails is listed and the scan goes on.
    if (failure.exit_code == kExitIo || s.aborted()) return failure;
    if (failure.exit_code == kExitProtocolTooOld) ++too_old;
    arms.push_back(
        {{"arm", arm}, {"found", failure.exit_code == kExitProtocolTooOld}, {"error", failure.json["error"]}});
    o.text += "arm " + std::to_string(arm) + ": " + failure.json["error"]["message"].get<std::string>() + "\n";
  }
  o.json = {{"command", "scan"}, {"bus", Describe(s.options().bus)}, {"arms", arms}};
  if (found + too_old == 0) {
    CommandOutcome f = ToolSession::Failure(kExitNoArm, "no arm answered on " + Describe(s.options().bus), o.json);
    return f;
  }
  o.json["ok"] = true;
  o.exit_code = kExitOk;
  return o;
}

CommandOutcome Info(ToolSession& s, int arm) {
  OpenedArm a;
  CommandOutcome failure;
  if (!OpenArm(s, arm, &a, &failure)) return failure;
  CommandOutcome o;
  try {
    const StoredImage image = ReadStoredCalibration(*a.link, a.info);
    const CalibrationValues values = ValuesOf(image.params);
    const NodeHeartbeat* hb = s.ObserverOf(arm)->heartbeat(arm);
    o.json = {{"command", "info"}, {"arm", arm}, {"ok", true}};
    o.json["node"] = ToJson(a.info, hb);
    o.json["calibration"] = ToJson(values);
    o.text = InfoText(a, hb) + "stored values:\n" + ValuesText(values);
  } catch (const cal::CalibrationAbort& e) {
    return AbortOutcome(e, "read", arm);
  }
  return o;
}

}  // namespace vesica::app::calibrate
