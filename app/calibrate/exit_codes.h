// vesica-calibrate's exit codes: scripts rely on them (docs/calibration.md lists them).
#pragma once

#include "device/calibration/calibration_abort.h"

namespace vesica::app::calibrate {

enum ExitCode : int {
  kExitOk = 0,
  kExitInternal = 1,        ///< a bug: an unexpected exception
  kExitUsage = 2,           ///< bad command line
  kExitNoArm = 3,           ///< unknown arm name, or no arm answered on the bus
  kExitProtocolTooOld = 4,  ///< the node's firmware predates calibration (protocol < 1.1)
  kExitFailed = 5,          ///< a step could not measure, the node refused, or a value is out of tolerance
  kExitAborted = 6,         ///< stopped before its end: Ctrl-C, declined prompt, E-stop, node fault, link lost
  kExitStorage = 7,         ///< a calibration image is corrupt, not one, for another arm, or a save failed
  kExitIo = 8,              ///< the bus or an output file could not be opened or written
};

/// Short stable name for JSON ("usage", "no_arm", ...).
const char* ExitName(int code);

/// Where a CalibrationAbort in `step` leaves the tool.
int ExitCodeOf(device::calibration::AbortReason reason, const std::string& step);

}  // namespace vesica::app::calibrate
