// cannelloni v2 packet writer and frame parser.
#include "firmware_protocol/transport/cannelloni_packet.h"

namespace vesica::fp {

namespace {
std::uint32_t linux_id(const CanFrame& f) {
  std::uint32_t id = f.id & (f.extended() ? 0x1FFFFFFFu : 0x7FFu);
  if (f.extended()) id |= kLinuxEffFlag;
  if (f.remote()) id |= kLinuxRtrFlag;
  return id;
}
}  // namespace

std::size_t cannelloni_frame_size(const CanFrame& f) {
  return 4 + 1 + (f.fd() ? 1 : 0) + (f.remote() ? 0 : f.len);
}

std::size_t write_cannelloni_packet(const CanFrame* frames, std::size_t count, std::uint8_t seq_no,
                                    std::uint8_t* out, std::size_t capacity) {
  std::size_t need = kCannelloniHeaderSize;
  for (std::size_t i = 0; i < count; ++i) need += cannelloni_frame_size(frames[i]);
  if (need > capacity || count > 0xFFFF) return 0;
  out[0] = kCannelloniVersion;
  out[1] = kCannelloniOpData;
  out[2] = seq_no;
  out[3] = static_cast<std::uint8_t>(count >> 8);
  out[4] = static_cast<std::uint8_t>(count);
  std::uint8_t* p = out + kCannelloniHeaderSize;
  for (std::size_t i = 0; i < count; ++i) {
    const CanFrame& f = frames[i];
    const std::uint32_t id = linux_id(f);
    *p++ = static_cast<std::uint8_t>(id >> 24);
    *p++ = static_cast<std::uint8_t>(id >> 16);
    *p++ = static_cast<std::uint8_t>(id >> 8);
    *p++ = static_cast<std::uint8_t>(id);
    *p++ = static_cast<std::uint8_t>(f.len | (f.fd() ? kCannelloniFdFlag : 0));
    if (f.fd()) *p++ = f.brs() ? kLinuxFdBrs : 0;
    if (!f.remote())
      for (std::uint8_t b = 0; b < f.len; ++b) *p++ = f.data[b];
  }
  return need;
}

namespace cannelloni_detail {
CannelloniError parse_frame(const std::uint8_t*& p, const std::uint8_t* end, CanFrame& f) {
  if (end - p < 5) return CannelloniError::Truncated;
  const std::uint32_t id = static_cast<std::uint32_t>(p[0]) << 24 | static_cast<std::uint32_t>(p[1]) << 16 |
                           static_cast<std::uint32_t>(p[2]) << 8 | p[3];
  const std::uint8_t len_byte = p[4];
  p += 5;
  const bool fd = (len_byte & kCannelloniFdFlag) != 0;
  const std::uint8_t len = static_cast<std::uint8_t>(len_byte & 0x7F);
  f = CanFrame{};
  if (fd) {
    if (end - p < 1) return CannelloniError::Truncated;
    f.flags = static_cast<std::uint8_t>(CanFrame::kFdFrame | ((*p & kLinuxFdBrs) ? CanFrame::kBitRateSwitch : 0));
    ++p;
    if (!is_valid_fd_length(len)) return CannelloniError::BadLength;
  } else if (len > kClassicMaxLength) {
    return CannelloniError::BadLength;
  }
  if (id & kLinuxEffFlag) f.flags |= CanFrame::kExtendedId;
  const bool rtr = (id & kLinuxRtrFlag) != 0;
  if (rtr) f.flags |= CanFrame::kRemote;
  f.id = id & ((id & kLinuxErrFlag) ? (0x1FFFFFFFu | kLinuxErrFlag) : (id & kLinuxEffFlag) ? 0x1FFFFFFFu : 0x7FFu);
  f.len = len;
  if (!rtr) {
    if (end - p < len) return CannelloniError::Truncated;
    for (std::uint8_t b = 0; b < len; ++b) f.data[b] = p[b];
    p += len;
  }
  return CannelloniError::None;
}
}  // namespace cannelloni_detail

const char* to_string(CannelloniError e) {
  switch (e) {
    case CannelloniError::None: return "none";
    case CannelloniError::Truncated: return "truncated";
    case CannelloniError::BadVersion: return "bad_version";
    case CannelloniError::BadOpCode: return "bad_op_code";
    case CannelloniError::BadLength: return "bad_length";
    case CannelloniError::TrailingBytes: return "trailing_bytes";
  }
  return "?";
}

}  // namespace vesica::fp
