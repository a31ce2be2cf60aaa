// Parameter values and their CRC-protected persistent image.
#include "firmware_protocol/node/parameter_store.h"

#include <cstring>

#include "firmware_protocol/node/crc32.h"

namespace vesica::fp {

std::uint32_t f32_bits(float v) {
  std::uint32_t u;
  std::memcpy(&u, &v, sizeof u);
  return u;
}
float bits_f32(std::uint32_t raw) {
  float v;
  std::memcpy(&v, &raw, sizeof v);
  return v;
}

namespace {
std::uint32_t default_raw(const ParameterSpec& s) {
  if (s.type == ParameterType::F32) return f32_bits(static_cast<float>(s.default_value));
  if (s.type == ParameterType::I32) return static_cast<std::uint32_t>(static_cast<std::int32_t>(s.default_value));
  return static_cast<std::uint32_t>(s.default_value);
}
void put_u32(std::uint8_t* p, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) p[i] = static_cast<std::uint8_t>(v >> (8 * i));
}
std::uint32_t get_u32(const std::uint8_t* p) {
  return static_cast<std::uint32_t>(p[0]) | (static_cast<std::uint32_t>(p[1]) << 8) |
         (static_cast<std::uint32_t>(p[2]) << 16) | (static_cast<std::uint32_t>(p[3]) << 24);
}
// Value inside [min, max] for its type (NaN is outside).
AbortCode range_check(const ParameterSpec& s, std::uint32_t raw) {
  double v;
  if (s.type == ParameterType::F32) {
    const float f = bits_f32(raw);
    if (f != f) return AbortCode::ValueTooHigh;
    v = f;
  } else if (s.type == ParameterType::I32) {
    v = static_cast<std::int32_t>(raw);
  } else {
    v = raw;
  }
  if (v < s.min) return AbortCode::ValueTooLow;
  if (v > s.max) return AbortCode::ValueTooHigh;
  return AbortCode::None;
}
}  // namespace

void ParameterStore::restore_defaults() {
  for (std::size_t i = 0; i < kParameterCount; ++i) raw_[i] = default_raw(kParameterSpecs[i]);
}

AbortCode ParameterStore::write(std::uint16_t index, ParameterType type, std::uint32_t raw) {
  const int slot = parameter_slot(index);
  if (slot < 0) return AbortCode::NoSuchParameter;
  const ParameterSpec& s = kParameterSpecs[slot];
  if (s.access == ParameterAccess::ReadOnly) return AbortCode::ReadOnly;
  if (type != s.type) return AbortCode::TypeMismatch;
  const AbortCode range = range_check(s, raw);
  if (range != AbortCode::None) return range;
  raw_[slot] = raw;
  return AbortCode::None;
}

AbortCode ParameterStore::read(std::uint16_t index, ParameterType& type, std::uint32_t& raw) const {
  const int slot = parameter_slot(index);
  if (slot < 0) return AbortCode::NoSuchParameter;
  type = kParameterSpecs[slot].type;
  raw = raw_[slot];
  return AbortCode::None;
}

bool ParameterStore::set_internal(std::uint16_t index, std::uint32_t raw) {
  const int slot = parameter_slot(index);
  if (slot < 0) return false;
  raw_[slot] = raw;
  return true;
}

bool ParameterStore::set_internal_f32(std::uint16_t index, float v) { return set_internal(index, f32_bits(v)); }

float ParameterStore::f32(std::uint16_t index) const {
  const int slot = parameter_slot(index);
  return slot < 0 ? 0.0f : bits_f32(raw_[slot]);
}

std::uint32_t ParameterStore::u32(std::uint16_t index) const {
  const int slot = parameter_slot(index);
  return slot < 0 ? 0u : raw_[slot];
}

std::size_t ParameterStore::serialize(std::uint8_t* out, std::size_t capacity, std::uint16_t layout) const {
  const std::size_t size = image_size_of_layout(layout);
  if (size == 0 || capacity < size) return 0;
  const std::size_t count = layout == 1 ? kLayout1ParameterCount : kParameterCount;
  put_u32(out, kMagic);
  out[4] = static_cast<std::uint8_t>(layout);
  out[5] = static_cast<std::uint8_t>(layout >> 8);
  out[6] = static_cast<std::uint8_t>(count);
  out[7] = static_cast<std::uint8_t>(count >> 8);
  for (std::size_t i = 0; i < count; ++i) {
    const ParameterSpec& s = kParameterSpecs[i];
    put_u32(out + 8 + 4 * i, s.persistent ? raw_[i] : default_raw(s));
  }
  const std::size_t body = size - 4;
  put_u32(out + body, crc32(out, body));
  return size;
}

StorageResult ParameterStore::deserialize(const std::uint8_t* in, std::size_t n, std::uint16_t* layout) {
  if (n < 8) return StorageResult::BadSize;
  if (get_u32(in) != kMagic) return StorageResult::BadMagic;
  const std::uint16_t version = static_cast<std::uint16_t>(in[4] | (in[5] << 8));
  const std::uint16_t count = static_cast<std::uint16_t>(in[6] | (in[7] << 8));
  const std::size_t size = image_size_of_layout(version);
  if (size == 0) return StorageResult::BadVersion;
  if (n < size || count != (version == 1 ? kLayout1ParameterCount : kParameterCount)) return StorageResult::BadSize;
  const std::size_t body = size - 4;
  if (crc32(in, body) != get_u32(in + body)) return StorageResult::BadCrc;
  std::uint32_t loaded[kParameterCount];
  for (std::size_t i = 0; i < kParameterCount; ++i) {
    const ParameterSpec& s = kParameterSpecs[i];
    if (i >= count) {
      loaded[i] = s.persistent ? default_raw(s) : raw_[i];  // migrated: absent from the older layout
      continue;
    }
    loaded[i] = s.persistent ? get_u32(in + 8 + 4 * i) : raw_[i];
    // A valid CRC over an out-of-range value means a writer bug: refuse the whole image.
    if (s.persistent && s.access == ParameterAccess::ReadWrite && range_check(s, loaded[i]) != AbortCode::None)
      return StorageResult::BadCrc;
  }
  for (std::size_t i = 0; i < kParameterCount; ++i) raw_[i] = loaded[i];
  if (layout) *layout = version;
  return StorageResult::Ok;
}

const char* to_string(StorageResult r) {
  switch (r) {
    case StorageResult::Ok: return "ok";
    case StorageResult::BadMagic: return "bad_magic";
    case StorageResult::BadVersion: return "bad_version";
    case StorageResult::BadSize: return "bad_size";
    case StorageResult::BadCrc: return "bad_crc";
  }
  return "?";
}

}  // namespace vesica::fp
