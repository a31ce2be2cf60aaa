// The node's two calibration slots (A and B) in non-volatile storage: each a header (generation,
// date, tool version, serial), the parameter image (parameter_store.h) and a CRC-32 over both.
// A save goes to the slot that is invalid or older, so the newest valid slot is never touched and
// an interrupted write can only spoil the slot being written (docs/protocol.md section 9).
// Use: SlotHeader h; std::size_t n = encode_slot(h, image, out); SlotCheck c = check_slot(buf, n);
//      int target = save_target(status, generation); choose_boot_slot(status, generation).
// Freestanding C++17, header-only: no heap, no exceptions.
#pragma once

#include <cstddef>
#include <cstdint>

#include "firmware_protocol/node/crc32.h"
#include "firmware_protocol/node/parameter_store.h"

namespace vesica::fp {

namespace slot {
inline constexpr std::uint32_t kMagic = 0x31534356;  // "VCS1"
// A slot's layout is its parameter image's: 2 is written (protocol 1.3), 1 (1.0 .. 1.2) still read.
inline constexpr std::uint16_t kLayoutVersion = ParameterStore::kLayoutVersion;
inline constexpr std::size_t kHeaderSize = 24;
// Bytes of a slot of a layout (0: unknown layout).
constexpr std::size_t size_of_layout(std::uint16_t layout) {
  return ParameterStore::image_size_of_layout(layout) == 0
             ? 0
             : kHeaderSize + ParameterStore::image_size_of_layout(layout) + 4;
}
inline constexpr std::size_t kSize = size_of_layout(kLayoutVersion);  // the largest: read this many
inline constexpr std::size_t kLayout1Size = size_of_layout(1);
// Slots start on 256-byte boundaries (a flash sector each), A at 0, B at kStride. Boards in the
// field have B at 512: a layout that outgrew it would orphan their slot B.
inline constexpr std::size_t kStride = 512;
static_assert(kSize <= kStride && kLayout1Size <= kSize, "a slot must fit its 512-byte stride");
inline constexpr int kCount = 2;
inline constexpr std::uint32_t kNoSlot = 0xFF;  // active_slot when the node runs on defaults
constexpr std::size_t offset(int s) { return static_cast<std::size_t>(s) * kStride; }
}  // namespace slot

// What the slot header records about the calibration it carries.
struct SlotHeader {
  std::uint32_t generation = 0;    // 1 for the first save; the newest valid slot is booted
  std::uint32_t date_s = 0;        // Unix time of the calibration, from the tool
  std::uint32_t tool_version = 0;  // version of the tool that calibrated (major << 16 | minor << 8 | patch)
  std::uint32_t serial = 0;        // the board's serial when saved
};

// A slot's state as read back: Ok, BadMagic (blank/erased), BadVersion, BadSize, BadCrc; for an Ok
// slot its layout (1 or 2) and size in bytes.
struct SlotCheck {
  StorageResult status = StorageResult::BadMagic;
  SlotHeader header{};
  std::uint16_t layout = 0;
  std::size_t size = 0;
};

namespace slot_detail {
inline void put_u32(std::uint8_t* p, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) p[i] = static_cast<std::uint8_t>(v >> (8 * i));
}
inline std::uint32_t get_u32(const std::uint8_t* p) {
  return static_cast<std::uint32_t>(p[0]) | (static_cast<std::uint32_t>(p[1]) << 8) |
         (static_cast<std::uint32_t>(p[2]) << 16) | (static_cast<std::uint32_t>(p[3]) << 24);
}
}  // namespace slot_detail

// Writes header + image + CRC into out (capacity >= the slot's size); the layout is the image's
// (ParameterStore::serialize). Returns bytes written or 0.
inline std::size_t encode_slot(const SlotHeader& h, const std::uint8_t* image, std::size_t image_size,
                               std::uint8_t* out, std::size_t capacity) {
  using namespace slot_detail;
  const std::uint16_t layout = image_size == ParameterStore::kImageSize          ? 2
                               : image_size == ParameterStore::kLayout1ImageSize ? 1
                                                                                 : 0;
  const std::size_t size = slot::size_of_layout(layout);
  if (layout == 0 || capacity < size) return 0;
  put_u32(out, slot::kMagic);
  out[4] = static_cast<std::uint8_t>(layout);
  out[5] = static_cast<std::uint8_t>(layout >> 8);
  out[6] = static_cast<std::uint8_t>(image_size);
  out[7] = static_cast<std::uint8_t>(image_size >> 8);
  put_u32(out + 8, h.generation);
  put_u32(out + 12, h.date_s);
  put_u32(out + 16, h.tool_version);
  put_u32(out + 20, h.serial);
  for (std::size_t i = 0; i < image_size; ++i) out[slot::kHeaderSize + i] = image[i];
  const std::size_t body = size - 4;
  put_u32(out + body, crc32(out, body));
  return size;
}

// Checks a slot read from storage (n: the bytes read, slot::kSize from a slot's start, or exactly
// the slot from a file); the parameter image inside is checked by ParameterStore later.
inline SlotCheck check_slot(const std::uint8_t* in, std::size_t n) {
  using namespace slot_detail;
  SlotCheck c;
  if (n < slot::kLayout1Size) {
    c.status = StorageResult::BadSize;
    return c;
  }
  if (get_u32(in) != slot::kMagic) {
    // Erased flash reads 0xFF; anything else without the magic is a torn or foreign write.
    bool erased = true;
    for (std::size_t i = 0; i < slot::kLayout1Size && erased; ++i) erased = in[i] == 0xFF || in[i] == 0x00;
    c.status = erased ? StorageResult::BadMagic : StorageResult::BadCrc;
    return c;
  }
  const std::uint16_t version = static_cast<std::uint16_t>(in[4] | (in[5] << 8));
  const std::uint16_t payload = static_cast<std::uint16_t>(in[6] | (in[7] << 8));
  // The layout names the size the CRC covers. The CRC first: a torn header must read as corrupt,
  // not as a different version; a layout this firmware does not know is checked at its own size
  // (the largest it knows), so only an intact slot of a newer tool reads as BadVersion.
  const std::size_t known = slot::size_of_layout(version);
  const std::size_t size = known != 0 ? known : slot::kSize;
  if (n < size) {
    c.status = StorageResult::BadSize;
    return c;
  }
  const std::size_t body = size - 4;
  if (crc32(in, body) != get_u32(in + body)) {
    c.status = StorageResult::BadCrc;
    return c;
  }
  if (known == 0) {
    c.status = StorageResult::BadVersion;
    return c;
  }
  if (payload != ParameterStore::image_size_of_layout(version)) {
    c.status = StorageResult::BadSize;
    return c;
  }
  c.header = SlotHeader{get_u32(in + 8), get_u32(in + 12), get_u32(in + 16), get_u32(in + 20)};
  c.layout = version;
  c.size = size;
  c.status = StorageResult::Ok;
  return c;
}

// The valid slot with the highest generation, or -1 when neither is valid.
inline int choose_boot_slot(const StorageResult (&status)[slot::kCount],
                            const std::uint32_t (&generation)[slot::kCount]) {
  int best = -1;
  for (int s = 0; s < slot::kCount; ++s) {
    if (status[s] != StorageResult::Ok) continue;
    if (best < 0 || generation[s] > generation[best]) best = s;
  }
  return best;
}

// Where the next save goes: never the newest valid slot. An invalid slot first (A before B), else
// the older of two valid ones.
inline int save_target(const StorageResult (&status)[slot::kCount], const std::uint32_t (&generation)[slot::kCount]) {
  const int newest = choose_boot_slot(status, generation);
  if (newest < 0) return 0;
  return newest == 0 ? 1 : 0;
}

}  // namespace vesica::fp
