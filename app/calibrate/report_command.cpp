// report: the calibration in force on an arm, as a report (JSON + HTML) with a copy of its image.
// Nothing moves; the measurements of the calibration itself are in the report calibrate wrote.
#include <filesystem>

#include "app/calibrate/calibration_report.h"
#include "app/calibrate/commands.h"
#include "app/calibrate/exit_codes.h"
#include "app/calibrate/json_views.h"
#include "app/calibrate/open_arm.h"
#include "device/calibration/calibration_abort.h"

namespace vesica::app::calibrate {

namespace cal = device::calibration;
using nlohmann::json;

CommandOutcome Report(ToolSession& s, int arm) {
  OpenedArm a;
  CommandOutcome failure;
  if (!OpenArm(s, arm, &a, &failure)) return failure;
  StoredImage image;
  try {
    image = ReadStoredCalibration(*a.link, a.info);
  } catch (const cal::CalibrationAbort& e) {
    return AbortOutcome(e, "read", arm);
  }
  ReportInput in;
  in.kind = "stored calibration";
  in.arm = arm;
  in.info = a.info;
  in.before = ValuesOf(image.params);
  const NodeHeartbeat* hb = s.ObserverOf(arm)->heartbeat(arm);
  in.state = hb ? fp::to_string(hb->state) : "unknown";
  in.bus = s.where(arm);
  in.date_s = s.date_s();
  json doc = json::object();
  std::string error;
  const std::string stem = "arm" + std::to_string(arm) + "-stored";
  if (a.info.active_slot >= 0) {
    if (!WriteImageFile(s.session_dir() + "/" + stem + ".vcal", image, &error))
      return ToolSession::Failure(kExitIo, error);
    doc["files"]["image_stored"] = stem + ".vcal";
  }
  ReportFiles files;
  if (!WriteReport(in, s.session_dir(), stem, doc, &files, &error)) return ToolSession::Failure(kExitIo, error);
  CommandOutcome o;
  o.json = doc;
  o.json["command"] = "report";
  o.json["ok"] = true;
  o.json["session_dir"] = s.session_dir();
  o.text = a.text + ": " +
           (a.info.active_slot < 0 ? "no stored calibration (defaults in force)"
                                   : "calibration of " + DateText(a.info.calibration_date_s) + " in slot " +
                                         SlotName(a.info.active_slot)) +
           "\n" + ValuesText(in.before) + "report: " + files.html + "\n";
  return o;
}

}  // namespace vesica::app::calibrate
