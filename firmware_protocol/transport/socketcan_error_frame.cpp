// Mapping of SocketCAN error frames to bus states (linux/can/error.h).
#include "firmware_protocol/transport/socketcan_error_frame.h"

#include <linux/can.h>
#include <linux/can/error.h>

namespace vesica::fp {

ErrorFrameEffect interpret_error_frame(std::uint32_t can_id, const std::uint8_t data[8]) {
  ErrorFrameEffect e;
  e.error_class = can_id & CAN_ERR_MASK;
  if (can_id & CAN_ERR_BUSOFF) {
    e.has_state = true;
    e.state = BusState::BusOff;
  } else if (can_id & CAN_ERR_RESTARTED) {
    e.has_state = true;
    e.state = BusState::ErrorActive;
  } else if (can_id & CAN_ERR_CRTL) {
    const std::uint8_t c = data[1];
    if (c & (CAN_ERR_CRTL_RX_PASSIVE | CAN_ERR_CRTL_TX_PASSIVE)) {
      e.has_state = true;
      e.state = BusState::ErrorPassive;
    } else if (c & (CAN_ERR_CRTL_RX_WARNING | CAN_ERR_CRTL_TX_WARNING)) {
      e.has_state = true;
      e.state = BusState::ErrorWarning;
    } else if (c & CAN_ERR_CRTL_ACTIVE) {
      e.has_state = true;
      e.state = BusState::ErrorActive;
    }
    e.overflow = (c & (CAN_ERR_CRTL_RX_OVERFLOW | CAN_ERR_CRTL_TX_OVERFLOW)) != 0;
  }
  return e;
}

}  // namespace vesica::fp
