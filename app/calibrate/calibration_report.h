// A calibration's report: one JSON document (stable keys) and an HTML page made from it, with
// every measured value, its tolerance and pass/fail, the stored values before and after, the
// friction fit and range sweep plots (PNG) and the files that go with it (image copy, bus log).
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "app/calibrate/calibration_run.h"
#include "app/calibrate/stored_calibration.h"
#include "device/calibration/node_info.h"

namespace vesica::app::calibrate {

struct ReportInput {
  std::string kind = "calibration";  ///< "calibration", "verification", "stored calibration"
  int arm = 0;
  unsigned joints = 0b111;
  device::calibration::NodeInfo info;  ///< before
  std::optional<device::calibration::NodeInfo> info_after;
  CalibrationValues before;
  std::optional<CalibrationValues> after;
  const RunOutcome* run = nullptr;  ///< null: no measurement (report of what is stored)
  std::string state;                ///< the node's state as seen ("pre-operational")
  std::string bus;                  ///< where the arm was reached
  std::uint32_t date_s = 0;
};

struct ReportFiles {
  std::string json, html, friction_png, range_png;
};

/// The report's JSON (also what `--json` prints for the command).
nlohmann::json ReportJson(const ReportInput& in);
/// Writes <dir>/<stem>.json, .html and the plots; `files` named in the JSON under "files" (with
/// those already there, e.g. the image copy). False with a message.
bool WriteReport(const ReportInput& in, const std::string& dir, const std::string& stem, nlohmann::json& doc,
                 ReportFiles* files, std::string* error);
/// The HTML page of a report JSON (self-contained but for the PNGs beside it).
std::string ReportHtml(const nlohmann::json& doc);

}  // namespace vesica::app::calibrate
