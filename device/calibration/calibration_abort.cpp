#include "device/calibration/calibration_abort.h"

namespace vesica::device::calibration {

const char* ToString(AbortReason r) {
  switch (r) {
    case AbortReason::kNone:
      return "none";
    case AbortReason::kNodeFault:
      return "node_fault";
    case AbortReason::kEmergencyStop:
      return "emergency_stop";
    case AbortReason::kLinkLost:
      return "link_lost";
    case AbortReason::kAbortRequested:
      return "abort_requested";
    case AbortReason::kProtocolTooOld:
      return "protocol_too_old";
    case AbortReason::kRefused:
      return "refused";
    case AbortReason::kNoAnswer:
      return "no_answer";
    case AbortReason::kMeasurement:
      return "measurement";
  }
  return "?";
}

}  // namespace vesica::device::calibration
