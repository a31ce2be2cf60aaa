#include "app/calibrate/open_arm.h"

#include "app/calibrate/exit_codes.h"
#include "app/calibrate/json_views.h"
#include "device/calibration/calibration_abort.h"

namespace vesica::app::calibrate {

namespace cal = device::calibration;

CommandOutcome AbortOutcome(const cal::CalibrationAbort& e, const std::string& step, int arm) {
  const int code = ExitCodeOf(e.reason(), step);
  std::string message = "arm " + std::to_string(arm) + ": " + e.what();
  CommandOutcome o = ToolSession::Failure(code, message, {{"arm", arm}});
  o.json["error"]["reason"] = cal::ToString(e.reason());
  o.json["error"]["step"] = step;
  return o;
}

bool OpenArm(ToolSession& s, int arm, OpenedArm* out, CommandOutcome* failure) {
  std::string error;
  out->arm = arm;
  out->link = s.LinkTo(arm, &error);
  if (!out->link) {
    *failure = ToolSession::Failure(kExitIo, "arm " + std::to_string(arm) + ": " + error, {{"arm", arm}});
    return false;
  }
  try {
    out->info = cal::ReadNodeInfo(*out->link);
  } catch (const cal::CalibrationAbort& e) {
    *failure = AbortOutcome(e, "connect", arm);
    if (e.reason() == cal::AbortReason::kNoAnswer)
      *failure = ToolSession::Failure(
          kExitNoArm,
          "arm " + std::to_string(arm) + ": no answer from " + s.where(arm) + " (is the arm powered and on this bus?)",
          {{"arm", arm}});
    return false;
  }
  out->text = "arm " + std::to_string(arm) + " (node " + std::to_string(out->info.identity.node) + ", serial " +
              SerialText(out->info.identity.serial) + ")";
  return true;
}

}  // namespace vesica::app::calibrate
