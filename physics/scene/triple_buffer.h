#pragma once
// Wait-free hand-over of the latest value from one writer thread to one reader thread
// (docs/architecture.md: loops hand data through snapshots). The writer fills its own slot and swaps
// it with the shared middle one; the reader swaps the middle one in only when it is new. Neither
// side ever blocks or sees a half-written value.

#include <array>
#include <atomic>
#include <cstdint>

namespace vesica::physics {

template <class T>
class TripleBuffer {
 public:
  TripleBuffer() = default;
  explicit TripleBuffer(const T& initial) : slots_{initial, initial, initial} {}

  /// Writer thread only.
  void Publish(const T& value) {
    slots_[back_] = value;
    back_ = middle_.exchange(static_cast<std::uint8_t>(back_ | kFresh), std::memory_order_acq_rel) & kIndex;
  }

  /// Reader thread only: the most recently published value (or the initial one).
  const T& Latest() {
    if (middle_.load(std::memory_order_acquire) & kFresh)
      front_ = middle_.exchange(static_cast<std::uint8_t>(front_), std::memory_order_acq_rel) & kIndex;
    return slots_[front_];
  }

 private:
  static constexpr std::uint8_t kIndex = 0x3, kFresh = 0x4;
  std::array<T, 3> slots_{};
  std::uint8_t back_ = 0;                // writer's slot
  std::atomic<std::uint8_t> middle_{1};  // shared slot index, kFresh when unread
  std::uint8_t front_ = 2;               // reader's slot
};

}  // namespace vesica::physics
