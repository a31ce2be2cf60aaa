// Names of transport states and events, for logs and test messages.
#include "firmware_protocol/transport/transport.h"

namespace vesica::fp {

const char* to_string(BusState s) {
  switch (s) {
    case BusState::ErrorActive: return "error_active";
    case BusState::ErrorWarning: return "error_warning";
    case BusState::ErrorPassive: return "error_passive";
    case BusState::BusOff: return "bus_off";
    case BusState::Down: return "down";
  }
  return "?";
}

const char* to_string(SendStatus s) {
  switch (s) {
    case SendStatus::Queued: return "queued";
    case SendStatus::DeadlineMissed: return "deadline_missed";
    case SendStatus::QueueFull: return "queue_full";
    case SendStatus::BusOff: return "bus_off";
    case SendStatus::Closed: return "closed";
    case SendStatus::Invalid: return "invalid";
  }
  return "?";
}

const char* to_string(BusEvent::Kind k) {
  switch (k) {
    case BusEvent::Kind::StateChanged: return "state_changed";
    case BusEvent::Kind::ErrorFrame: return "error_frame";
    case BusEvent::Kind::RxOverflow: return "rx_overflow";
    case BusEvent::Kind::TxDropped: return "tx_dropped";
    case BusEvent::Kind::DeviceLost: return "device_lost";
  }
  return "?";
}

}  // namespace vesica::fp
