// Encode and decode Vesica CAN messages (messages.h) to and from frames (can_frame.h).
// Use:
//   CanFrame f; if (encode(Message{JointState{...}}, f) == EncodeError::None) transport.send(f, ...);
//   Message m; DecodeError e = decode(f, m); if (e != DecodeError::None) counters.add(e);
//   SequenceTracker per cyclic stream rejects repeated/stale counters (DecodeError::BadCounter).
// Layouts come from message_table.h only. Freestanding C++17: no heap, no exceptions, no OS calls.
#pragma once

#include <cstdint>

#include "firmware_protocol/codec/can_frame.h"
#include "firmware_protocol/codec/message_table.h"
#include "firmware_protocol/codec/messages.h"

namespace vesica::fp {

enum class DecodeError : std::uint8_t {
  None = 0,
  UnknownId,      // id not in the identifier plan (incl. node 0 for per-node functions, 29-bit ids)
  RemoteFrame,    // RTR frames are not part of the protocol
  WrongLength,    // payload length differs from the message's fixed length
  OutOfRange,     // a field's raw value lies outside its documented range / enumeration
  Inconsistent,   // fields disagree (e.g. heartbeat CANopen byte vs state, EMCY code vs fault)
  BadCounter,     // sequence counter repeated or went backwards (SequenceTracker)
};
inline constexpr std::uint8_t kDecodeErrorCount = 7;

enum class EncodeError : std::uint8_t {
  None = 0,
  BadNode,     // per-node message with node outside 1..127
  OutOfRange,  // a value outside its field's range (never silently saturated)
};

const char* to_string(DecodeError e);
const char* to_string(EncodeError e);

// Counted, named decode errors (one counter per DecodeError).
struct DecodeErrorCounters {
  std::uint32_t count[kDecodeErrorCount] = {};
  void add(DecodeError e) {
    if (e != DecodeError::None) ++count[static_cast<std::uint8_t>(e)];
  }
  std::uint32_t operator[](DecodeError e) const { return count[static_cast<std::uint8_t>(e)]; }
  std::uint32_t total() const {
    std::uint32_t t = 0;
    for (std::uint8_t i = 1; i < kDecodeErrorCount; ++i) t += count[i];
    return t;
  }
};

inline constexpr std::uint8_t kMaxNodeId = 127;

// Identifier of a message for a node (node ignored for broadcast messages).
constexpr std::uint16_t can_id(MessageKind kind, std::uint8_t node) {
  const MessageSpec& s = spec_of(kind);
  return static_cast<std::uint16_t>(s.per_node ? s.base_id + node : s.base_id);
}

// Which message an identifier carries; false if the id is not in the plan.
bool classify_id(std::uint32_t id, MessageKind& kind, std::uint8_t& node);

MessageKind kind_of(const Message& m);
std::uint8_t node_of(const Message& m);  // 0 for broadcast messages

EncodeError encode(const Message& message, CanFrame& out);
DecodeError decode(const CanFrame& frame, Message& out);

// Receiver-side check of a cyclic frame's 8-bit counter. A repeat or a jump of more than half the
// counter range (a stale/replayed frame) is BadCounter; smaller forward jumps are accepted and
// counted as lost frames.
class SequenceTracker {
 public:
  DecodeError check(std::uint8_t counter) {
    if (!primed_) {
      primed_ = true;
      last_ = counter;
      return DecodeError::None;
    }
    const std::uint8_t delta = static_cast<std::uint8_t>(counter - last_);
    if (delta == 0 || delta > 128) return DecodeError::BadCounter;
    lost_ += static_cast<std::uint32_t>(delta - 1);
    last_ = counter;
    return DecodeError::None;
  }
  void reset() { primed_ = false; }
  std::uint32_t lost_frames() const { return lost_; }

 private:
  bool primed_ = false;
  std::uint8_t last_ = 0;
  std::uint32_t lost_ = 0;
};

}  // namespace vesica::fp
