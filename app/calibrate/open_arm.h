// The first thing every arm command does: open the link to the arm, say hello (protocol check)
// and read what the node is (NodeInfo). Failures become the command's outcome with the exit code
// scripts expect: no arm (3), protocol too old (4), I/O (8), aborted (6).
#pragma once

#include "app/calibrate/tool_session.h"
#include "device/calibration/calibration_abort.h"
#include "device/calibration/calibration_link.h"
#include "device/calibration/node_info.h"

namespace vesica::app::calibrate {

struct OpenedArm {
  int arm = 0;
  device::calibration::CalibrationLink* link = nullptr;
  device::calibration::NodeInfo info;
  std::string text;  ///< "arm 1 (node 1, serial 0x5E51CA01)"
};

/// False with *failure filled in.
bool OpenArm(ToolSession& s, int arm, OpenedArm* out, CommandOutcome* failure);

/// The outcome of a CalibrationAbort thrown in `step`.
CommandOutcome AbortOutcome(const device::calibration::CalibrationAbort& e, const std::string& step, int arm);

}  // namespace vesica::app::calibrate
