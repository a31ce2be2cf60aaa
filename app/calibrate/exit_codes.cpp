#include "app/calibrate/exit_codes.h"

#include <string>

namespace vesica::app::calibrate {

const char* ExitName(int code) {
  switch (code) {
    case kExitOk:
      return "ok";
    case kExitInternal:
      return "internal";
    case kExitUsage:
      return "usage";
    case kExitNoArm:
      return "no_arm";
    case kExitProtocolTooOld:
      return "protocol_too_old";
    case kExitFailed:
      return "failed";
    case kExitAborted:
      return "aborted";
    case kExitStorage:
      return "storage";
    case kExitIo:
      return "io";
  }
  return "unknown";
}

int ExitCodeOf(device::calibration::AbortReason reason, const std::string& step) {
  using device::calibration::AbortReason;
  switch (reason) {
    case AbortReason::kNone:
      return kExitOk;
    case AbortReason::kProtocolTooOld:
      return kExitProtocolTooOld;
    // Silence at the first Hello means nothing is there; later it is a failed step.
    case AbortReason::kNoAnswer:
      return step == "connect" ? kExitNoArm : kExitFailed;
    case AbortReason::kAbortRequested:
    case AbortReason::kEmergencyStop:
    case AbortReason::kNodeFault:
    case AbortReason::kLinkLost:
      return kExitAborted;
    case AbortReason::kRefused:
      return step == "save" ? kExitStorage : kExitFailed;
    case AbortReason::kMeasurement:
      return kExitFailed;
  }
  return kExitFailed;
}

}  // namespace vesica::app::calibrate
