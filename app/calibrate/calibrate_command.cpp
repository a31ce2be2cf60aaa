// calibrate and verify: the arm moves. One prompt before the session opens (the node's watchdog
// would end a session left waiting for a person), then the steps with progress, then the checks.
#include <algorithm>
#include <chrono>
#include <filesystem>

#include "app/calibrate/calibration_report.h"
#include "app/calibrate/calibration_run.h"
#include "app/calibrate/commands.h"
#include "app/calibrate/exit_codes.h"
#include "app/calibrate/json_views.h"
#include "app/calibrate/open_arm.h"
#include "app/calibrate/stored_calibration.h"
#include "device/calibration/calibration_abort.h"
#include "firmware_protocol/emulator/reference_load.h"

namespace vesica::app::calibrate {

namespace cal = device::calibration;
using nlohmann::json;

namespace {

MotionNotice NoticeFor(const OpenedArm& a, const CalibrateRequest& r) {
  MotionNotice n;
  n.arm = a.arm;
  n.arm_text = a.text;
  n.max_current_A = r.max_current_A;
  std::string joints;
  for (int j = 0; j < 3; ++j)
    if ((r.joints >> j) & 1u) joints += std::string(joints.empty() ? "" : ", ") + JointName(j);
  for (Step s : r.steps) {
    const StepInfo& i = InfoOf(s);
    if (!i.motion) continue;
    // Gravity holds move pitch only.
    const std::string which = s == Step::kGravity ? ((r.joints >> 1) & 1u ? "pitch" : "") : joints;
    if (!which.empty()) n.motions.push_back(std::string(i.name) + ": " + i.motion + " (" + which + ")");
  }
  return n;
}

std::string StoredImageName(const StoredImage& i) {
  return "serial-" + SerialText(i.header.serial).substr(2) + "-gen-" + std::to_string(i.header.generation) + ".vcal";
}

// A copy in the session folder and in the archive restore --slot reads.
bool KeepImage(ToolSession& s, const StoredImage& image, const std::string& name, std::string* path,
               std::string* error) {
  std::error_code ec;
  std::filesystem::create_directories(s.image_archive(), ec);
  *path = s.session_dir() + "/" + name;
  return WriteImageFile(*path, image, error) &&
         WriteImageFile(s.image_archive() + "/" + StoredImageName(image), image, error);
}

CommandOutcome Measure(ToolSession& s, int arm, const CalibrateRequest& request, bool save) {
  const char* command = save ? "calibrate" : "verify";
  OpenedArm a;
  CommandOutcome failure;
  if (!OpenArm(s, arm, &a, &failure)) return failure;
  StoredImage before;
  try {
    before = ReadStoredCalibration(*a.link, a.info);
  } catch (const cal::CalibrationAbort& e) {
    return AbortOutcome(e, "read", arm);
  }
  const CalibrationValues stored = ValuesOf(before.params);
  if (!save && a.info.active_slot < 0)
    return ToolSession::Failure(kExitFailed,
                                "arm " + std::to_string(arm) +
                                    " has no stored calibration to verify; run "
                                    "`vesica-calibrate calibrate " +
                                    std::to_string(arm) + "` first",
                                {{"arm", arm}});
  // A step alone starts from the stored calibration (range, directions): a blank arm has none.
  const bool partial = request.steps != AllStepList() && request.steps != std::vector<Step>{Step::kCurrentOffset};
  if (save && partial && a.info.active_slot < 0)
    return ToolSession::Failure(kExitFailed,
                                "arm " + std::to_string(arm) + " has no stored calibration for --step " +
                                    InfoOf(request.steps.front()).name +
                                    " to start from; run a whole calibration first (nothing moved)",
                                {{"arm", arm}});
  const MotionNotice notice = NoticeFor(a, request);
  if (!notice.motions.empty() && !s.ui().ConfirmMotion(notice))  // the hand steps move no motor
    return ToolSession::Failure(kExitAborted,
                                "arm " + std::to_string(arm) +
                                    ": not confirmed; nothing moved, nothing "
                                    "was written",
                                {{"arm", arm}});
  // The torque-constant check and the guided hand steps alone store what they measured on a node
  // of protocol 1.3 (image layout 2); an older node has no place for it: a check, nothing saved.
  const bool layout2 = a.link->negotiated_minor() != 0xFF && a.link->negotiated_minor() >= fp::kLayout2Minor;
  const bool check_only =
      !layout2 && std::none_of(request.steps.begin(), request.steps.end(), [](Step x) { return InfoOf(x).in_whole; });
  const bool measures_layout2 = std::any_of(request.steps.begin(), request.steps.end(), [](Step x) {
    return x == Step::kTorqueConstant || x == Step::kRollOffset || x == Step::kJawSpan || x == Step::kPedalTravel;
  });
  if (measures_layout2 && !layout2)
    s.ui().Note(a.text + ": node " + std::to_string(a.link->node_id()) + " speaks protocol 1." +
                std::to_string(a.link->negotiated_minor()) +
                ": the torque-constant correction and the hand sensors' calibration are measured and reported but "
                "not stored (they need 1.3; update the arm's firmware)");
  // The emulated arms have the reference load fixture in their emulator: it is clamped on here.
  const bool torque_check =
      std::find(request.steps.begin(), request.steps.end(), Step::kTorqueConstant) != request.steps.end();
  if (torque_check && s.bus().emulated_arm(arm))
    s.bus().emulated_arm(arm)->plant().SetReferenceLoad(fp::emulator::StandardReferenceLoad());
  RunRequest run;
  run.plan.joints = static_cast<std::uint8_t>(request.joints);
  run.plan.session_max_current_A = request.max_current_A;
  run.plan.date_s = s.date_s();
  run.plan.tool_version = kToolVersion;
  run.plan.progress = [&s, arm](const std::string& step, double f) { s.Progress(arm, step, f); };
  // The guided hand steps ask the person through the UI, at most every 20 ms of bus time (the
  // servo period goes on between: the node's watchdog is fed).
  run.plan.hand_guide = [&s, arm, text = a.text, link = a.link, last = -1.0, shown = std::string()](
                            const cal::HandPromptSpec& p, double live) mutable {
    const std::string key = p.step + "/" + std::to_string(p.prompt_index) + "/" + std::to_string(p.attempt);
    if (key == shown && link->now_s() - last < 0.02) return cal::HandReply::kWait;
    shown = key;
    last = link->now_s();
    HandPrompt prompt{arm,       text,          p.step, p.instruction, "counts", p.prompt_index, p.prompt_count,
                      p.attempt, p.retry_reason};
    switch (s.ui().GuideHand(prompt, live)) {
      case HandAnswer::kAccept:
        return cal::HandReply::kAccept;
      case HandAnswer::kRetry:
        return cal::HandReply::kRetry;
      case HandAnswer::kAbort:
        return cal::HandReply::kAbort;
      case HandAnswer::kWait:
        break;
    }
    return cal::HandReply::kWait;
  };
  run.steps = request.steps;
  run.save = save && !check_only;
  const unsigned joints = request.joints;
  if (save)
    run.judge = [joints](const cal::CalibrationResult& r, const std::vector<Step>& steps) {
      return AcceptanceChecks(r, joints, steps);
    };
  else
    run.judge = [joints, stored, margin = run.plan.range_margin](const cal::CalibrationResult& r,
                                                                 const std::vector<Step>& steps) {
      return VerifyChecks(r, stored, joints, steps, margin);
    };
  s.ui().Note(a.text + ": " + command + " (" + Describe(s.options().bus) + ")");
  const RunOutcome out = RunCalibration(*a.link, *s.ObserverOf(arm), run);
  if (out.result.abort != cal::AbortReason::kNone) {
    CommandOutcome o =
        AbortOutcome(cal::CalibrationAbort(out.result.abort, out.result.message), out.result.failed_step, arm);
    o.json["command"] = command;
    return o;
  }
  // The report: measured values, checks, before and after.
  ReportInput in;
  in.kind = save ? "calibration" : "verification";
  in.arm = arm;
  in.joints = joints;
  in.info = a.info;
  in.before = stored;
  in.run = &out;
  in.state =
      fp::to_string(s.ObserverOf(arm)->heartbeat(arm) ? s.ObserverOf(arm)->heartbeat(arm)->state : fp::NodeState::Boot);
  in.bus = s.where(arm);
  in.date_s = s.date_s();
  json doc = json::object();
  std::string error, before_path, after_path;
  try {
    if (a.info.active_slot >= 0 &&
        !KeepImage(s, before, "arm" + std::to_string(arm) + "-before.vcal", &before_path, &error))
      return ToolSession::Failure(kExitIo, error);
    if (out.result.saved) {
      const cal::NodeInfo after_info = cal::ReadNodeInfo(*a.link);
      const StoredImage after = ReadStoredCalibration(*a.link, after_info);
      in.info_after = after_info;
      in.after = ValuesOf(after.params);
      if (!KeepImage(s, after, "arm" + std::to_string(arm) + "-stored.vcal", &after_path, &error))
        return ToolSession::Failure(kExitIo, error);
    }
  } catch (const cal::CalibrationAbort& e) {
    return AbortOutcome(e, "read back", arm);
  }
  if (!before_path.empty()) doc["files"]["image_before"] = std::filesystem::path(before_path).filename().string();
  if (!after_path.empty()) doc["files"]["image_stored"] = std::filesystem::path(after_path).filename().string();
  ReportFiles files;
  const auto render_start = std::chrono::steady_clock::now();
  if (!WriteReport(in, s.session_dir(), "arm" + std::to_string(arm) + "-" + command, doc, &files, &error))
    return ToolSession::Failure(kExitIo, error);
  CommandOutcome o;
  o.json = doc;
  // Wall time of the report (plots, HTML, JSON): printed, not in the report file, which stays
  // the same for the same arm.
  o.json["report_write_s"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - render_start).count();
  o.json["command"] = command;
  o.json["session_dir"] = s.session_dir();
  o.json["ok"] = !out.out_of_tolerance;
  std::string result_line;
  if (out.out_of_tolerance) {
    o.exit_code = kExitFailed;
    o.json["error"] = {
        {"code", kExitFailed},
        {"name", ExitName(kExitFailed)},
        {"message", "arm " + std::to_string(arm) + ": " +
                        (save ? out.result.message : std::string("the arm no longer matches its stored calibration"))}};
    result_line = "FAIL: " + o.json["error"]["message"].get<std::string>();
  } else {
    result_line =
        check_only ? "PASS: every value is within its tolerance (nothing was written)"
        : save     ? "PASS: calibration saved in slot " + SlotName(in.info_after ? in.info_after->active_slot : -1) +
                     " (generation " +
                     std::to_string(
                         in.info_after && in.info_after->active_slot >= 0
                             ? in.info_after->slot_generation[static_cast<std::size_t>(in.info_after->active_slot)]
                             : 0) +
                     ")"
               : "PASS: the arm matches its stored calibration (nothing was written)";
  }
  char t[64];
  std::snprintf(t, sizeof t, "%.1f s of bus time", out.bus_time_s);
  o.text = a.text + ": " + command + ", " + t + "\n" + ChecksText(out.checks);
  if (in.after) o.text += "stored before:\n" + ValuesText(in.before) + "stored now:\n" + ValuesText(*in.after);
  o.text += result_line + "\nreport: " + files.html + "\n";
  return o;
}

}  // namespace

CommandOutcome Calibrate(ToolSession& s, int arm, const CalibrateRequest& request) {
  return Measure(s, arm, request, true);
}
CommandOutcome Verify(ToolSession& s, int arm, const CalibrateRequest& request) {
  return Measure(s, arm, request, false);
}

}  // namespace vesica::app::calibrate
