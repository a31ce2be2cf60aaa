// What a Linux SocketCAN error frame (CAN_ERR_FLAG set; linux/can/error.h) means for the bus state.
// Use: ErrorFrameEffect e = interpret_error_frame(can_id, data);  if (e.has_state) state = e.state;
// Pure function, so the mapping is tested without a CAN controller (vcan never produces errors).
#pragma once

#include <cstdint>

#include "firmware_protocol/transport/transport.h"

namespace vesica::fp {

struct ErrorFrameEffect {
  bool has_state = false;      // the frame implies a bus state
  BusState state = BusState::ErrorActive;
  bool overflow = false;       // controller RX/TX buffer overflow reported
  std::uint32_t error_class = 0;  // can_id & CAN_ERR_MASK (CAN_ERR_* class bits)
};

ErrorFrameEffect interpret_error_frame(std::uint32_t can_id, const std::uint8_t data[8]);

}  // namespace vesica::fp
