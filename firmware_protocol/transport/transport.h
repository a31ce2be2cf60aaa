// One interface for every CAN transport: SocketCAN (real hardware, vcan), the in-process virtual
// bus (bit-accurate, injected clock) and CAN over UDP (cannelloni packet format).
// Use:
//   SendStatus s = t.send(frame, t.now() + 500us);     // deadline on the transport's own clock
//   TimedFrame rx; while (t.receive(rx)) handle(rx.frame, rx.timestamp);   // non-blocking
//   BusEvent ev;   while (t.poll_event(ev)) log(ev);   // bus state changes, error frames, overflows
//   t.wait(1ms);   // block until something may be readable (returns at once on the virtual bus)
// Host side only (C++20, may use the OS in implementations; this header itself does not).
#pragma once

#include <chrono>
#include <cstdint>

#include "firmware_protocol/codec/can_frame.h"

namespace vesica::fp {

using Nanoseconds = std::chrono::nanoseconds;

struct TimedFrame {
  CanFrame frame;
  Nanoseconds timestamp{0};  // end of frame on the transport's clock (kernel/bus time when known)
};

enum class BusState : std::uint8_t { ErrorActive, ErrorWarning, ErrorPassive, BusOff, Down };

enum class SendStatus : std::uint8_t {
  Queued,          // accepted; will be (or was) transmitted
  DeadlineMissed,  // could not be handed to the bus before the deadline; frame dropped
  QueueFull,       // transmit queue full (ENOBUFS on SocketCAN); frame dropped, counted
  BusOff,          // controller is bus-off
  Closed,          // transport is not open / device vanished
  Invalid,         // frame not sendable on this transport (e.g. FD frame on a classic-only link)
};

struct BusEvent {
  enum class Kind : std::uint8_t {
    StateChanged,   // state holds the new BusState
    ErrorFrame,     // a bus error was seen (detail: transport-specific error class bits)
    RxOverflow,     // frames were lost on receive (detail: how many, if known)
    TxDropped,      // a queued frame was dropped (deadline or queue overflow; detail: id)
    DeviceLost,     // interface vanished (ENODEV/ENETDOWN)
  };
  Kind kind = Kind::ErrorFrame;
  BusState state = BusState::ErrorActive;
  std::uint32_t detail = 0;
  Nanoseconds timestamp{0};
};

const char* to_string(BusState s);
const char* to_string(SendStatus s);
const char* to_string(BusEvent::Kind k);

struct TransportStats {
  std::uint64_t tx_frames = 0;
  std::uint64_t rx_frames = 0;
  std::uint64_t tx_dropped = 0;      // deadline missed or queue full
  std::uint64_t rx_dropped = 0;      // receive overflow
  std::uint64_t error_frames = 0;
  std::uint64_t malformed = 0;       // undecodable transport packets (UDP), counted not crashed
  std::uint64_t foreign = 0;         // datagrams from other than the configured peer (UDP), dropped
};

class Transport {
 public:
  virtual ~Transport() = default;
  virtual SendStatus send(const CanFrame& frame, Nanoseconds deadline) = 0;
  virtual bool receive(TimedFrame& out) = 0;
  virtual bool poll_event(BusEvent& out) = 0;
  // Waits up to `timeout` for a frame or event; true if one may be available.
  virtual bool wait(Nanoseconds timeout) = 0;
  virtual Nanoseconds now() const = 0;
  virtual BusState state() const = 0;
  virtual TransportStats stats() const = 0;
};

}  // namespace vesica::fp
