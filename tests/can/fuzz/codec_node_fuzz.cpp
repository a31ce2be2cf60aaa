// libFuzzer target: arbitrary byte streams as CAN frames into the decoder and the reference node.
// Input: records [id_hi3 | flags << 3, id_lo, len, data[len <= 8], tick_dt (x 100 us)].
// Properties (trap on violation): decoded frames re-encode to the same bytes; every frame the node
// sends decodes; no current flows unless enabled (or in a calibration procedure or session), and
// never above the node's current limit.
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "firmware_protocol/codec/codec.h"
#include "firmware_protocol/node/node.h"

namespace {

using namespace vesica::fp;

struct FuzzHardware {
  HardwareSample sample;
  JointArray applied{};
  HardwareSample sense() { return sample; }
  void apply_currents(const JointArray& a) { applied = a; }
  bool storage_read(std::size_t, std::uint8_t*, std::size_t) { return false; }
  bool storage_write(std::size_t, const std::uint8_t*, std::size_t) { return true; }
};

void check(bool ok) {
  if (!ok) __builtin_trap();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  FuzzHardware hw;
  Node<FuzzHardware> node(hw, 1);
  std::uint64_t now_us = 0;
  node.boot(now_us);
  std::size_t i = 0;
  while (i + 3 <= size) {
    CanFrame f;
    f.id = static_cast<std::uint32_t>((data[i] & 0x07) << 8 | data[i + 1]);
    f.flags = static_cast<std::uint8_t>((data[i] >> 3) & (CanFrame::kExtendedId | CanFrame::kRemote));
    f.len = static_cast<std::uint8_t>(data[i + 2] % 9);
    i += 3;
    for (std::uint8_t b = 0; b < f.len && i < size; ++b) f.data[b] = data[i++];
    const std::uint8_t dt = i < size ? data[i++] : 10;

    Message m;
    if (decode(f, m) == DecodeError::None) {
      CanFrame again;
      check(encode(m, again) == EncodeError::None);
      check(again == f);
    }
    node.on_frame(f, now_us);
    now_us += 100u * dt;
    hw.sample.velocity = {0, 0, 0};
    node.tick(now_us);

    for (int j = 0; j < kJointCount; ++j) {
      check(std::isfinite(hw.applied[j]));
      if (!node.enabled())
        check(hw.applied[j] == 0.0f || node.calibration_status() == CalibrationStatus::Running ||
              node.calibration_session_open());
      // The drive's setpoint carries the current-sensor offset; the motor's current is bounded.
      const float offset =
          hw.applied[j] == 0.0f ? 0.0f : node.parameters().f32(static_cast<std::uint16_t>(param::kCurrentOffset + j));
      check(std::fabs(hw.applied[j] - offset) <=
            node.parameters().f32(static_cast<std::uint16_t>(param::kMaxCurrent + j)) + 1e-6f);
    }
    CanFrame out;
    while (node.pop_tx(out)) {
      Message sent;
      check(decode(out, sent) == DecodeError::None);
    }
  }
  return 0;
}
