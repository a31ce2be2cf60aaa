#pragma once

#include <stdexcept>
#include <string>

namespace vesica::device::calibration {

/// Why a calibration stopped before its end. Every one leaves the arm disabled (zero current),
/// and every one but kNone leaves the stored calibration in force (the node reloads it).
enum class AbortReason {
  kNone,
  kNodeFault,       ///< the node latched a fault (over-speed, over-current, watchdog, ...)
  kEmergencyStop,   ///< E-stop frame or open E-stop loop
  kLinkLost,        ///< no joint state for the link's loss timeout
  kAbortRequested,  ///< the technician stopped it (Ctrl-C, a button)
  kProtocolTooOld,  ///< the node's firmware predates the calibration session (protocol < 1.1)
  kRefused,         ///< the node refused a request (wrong state, parameter abort, ...)
  kNoAnswer,        ///< the node did not answer a request in time
  kMeasurement,     ///< a step could not measure what it needs (joint blocked, no stop found, ...)
};

const char* ToString(AbortReason r);

/// Thrown by the calibration link and procedures; what() says what happened, for the technician.
class CalibrationAbort : public std::runtime_error {
 public:
  CalibrationAbort(AbortReason reason, const std::string& what) : std::runtime_error(what), reason_(reason) {}
  AbortReason reason() const { return reason_; }

 private:
  AbortReason reason_;
};

}  // namespace vesica::device::calibration
