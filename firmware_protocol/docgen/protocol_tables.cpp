// Generates the protocol document's tables from the message, field, parameter and fault tables.
#include "firmware_protocol/docgen/protocol_tables.h"

#include <cstdio>
#include <sstream>

#include "firmware_protocol/codec/codec.h"
#include "firmware_protocol/codec/frame_timing.h"
#include "firmware_protocol/node/parameter_table.h"

namespace vesica::fp {
namespace {

std::string fmt(const char* f, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

std::string number(double v) {
  if (v == static_cast<double>(static_cast<long long>(v)) && v > -1e12 && v < 1e12) return fmt("%.0f", v);
  return fmt("%g", v);
}

const char* direction(Direction d) {
  switch (d) {
    case Direction::HostToNode: return "host→node";
    case Direction::NodeToHost: return "node→host";
    case Direction::Broadcast: return "any→all";
  }
  return "?";
}

const char* type_name(WireType t) {
  switch (t) {
    case WireType::U8: return "u8";
    case WireType::I8: return "i8";
    case WireType::U16: return "u16";
    case WireType::I16: return "i16";
    case WireType::U32: return "u32";
    case WireType::I32: return "i32";
  }
  return "?";
}

const char* param_type(ParameterType t) {
  switch (t) {
    case ParameterType::None: return "-";
    case ParameterType::U32: return "u32";
    case ParameterType::I32: return "i32";
    case ParameterType::F32: return "f32";
  }
  return "?";
}

std::string id_text(const MessageSpec& s) {
  char buf[32];
  std::snprintf(buf, sizeof buf, s.per_node ? "0x%03X+n" : "0x%03X", s.base_id);
  return buf;
}

std::string messages() {
  std::ostringstream o;
  o << "| Message | COB-ID | Direction | Bytes | Rate | Counter | Purpose |\n";
  o << "|---|---|---|---|---|---|---|\n";
  for (const MessageSpec& s : kMessageSpecs)
    o << "| " << s.name << " | " << id_text(s) << " | " << direction(s.direction) << " | " << int(s.length) << " | "
      << (s.rate_hz ? std::to_string(s.rate_hz) + " Hz" : std::string("event")) << " | "
      << (s.has_counter ? "yes" : "no") << " | " << s.purpose << " |\n";
  return o.str();
}

std::string fields_table() {
  std::ostringstream o;
  o << "| Message | Field | Byte | Bits | Type | LSB | Unit | Valid range (SI) |\n";
  o << "|---|---|---|---|---|---|---|---|\n";
  for (const FieldSpec* f : kAllFields) {
    const std::string bits = f->bit_width ? std::to_string(f->bit_offset) + ".." +
                                                std::to_string(f->bit_offset + f->bit_width - 1)
                                          : std::string("all");
    o << "| " << spec_of(f->message).name << " | " << f->name << " | " << int(f->offset) << " | " << bits << " | "
      << type_name(f->type) << " | " << number(f->lsb) << " | " << (*f->unit ? f->unit : "-") << " | "
      << number(f->min) << " .. " << number(f->max) << " |\n";
  }
  return o.str();
}

std::string parameters() {
  std::ostringstream o;
  o << "| Index | Name | Type | Unit | Range | Default | Access | Stored |\n";
  o << "|---|---|---|---|---|---|---|---|\n";
  for (const ParameterSpec& p : kParameterSpecs) {
    char idx[16];
    std::snprintf(idx, sizeof idx, "0x%04X", p.index);
    o << "| " << idx << " | " << p.name << " | " << param_type(p.type) << " | " << (*p.unit ? p.unit : "-") << " | "
      << number(p.min) << " .. " << number(p.max) << " | " << number(p.default_value) << " | "
      << (p.access == ParameterAccess::ReadOnly ? "ro" : "rw") << " | " << (p.persistent ? "yes" : "no") << " |\n";
  }
  return o.str();
}

std::string faults() {
  std::ostringstream o;
  o << "| Fault byte | Name | EMCY error code | Error register |\n";
  o << "|---|---|---|---|\n";
  for (std::uint8_t i = 0; i < kFaultCodeCount; ++i) {
    const auto f = static_cast<FaultCode>(i);
    char code[16], reg[16];
    std::snprintf(code, sizeof code, "0x%04X", emcy_error_code(f));
    std::snprintf(reg, sizeof reg, "0x%02X", emcy_error_register(f));
    o << "| " << int(i) << " | " << to_string(f) << " | " << code << " | " << reg << " |\n";
  }
  return o.str();
}

std::string bandwidth() {
  const BitRates rates;
  const int arms = 2;
  std::ostringstream o;
  o << "| Message | Bytes | Rate per arm | Classic worst-case bits | Classic load (2 arms) | CAN FD worst-case µs | CAN FD load (2 arms) |\n";
  o << "|---|---|---|---|---|---|---|\n";
  double classic_total = 0, fd_total = 0;
  for (const MessageSpec& s : kMessageSpecs) {
    if (s.rate_hz == 0 || !s.per_node || s.kind == MessageKind::CalibrationProgress) continue;
    const std::uint32_t bits = classic_worst_case_bits(s.length);
    const double classic = arms * s.rate_hz * bits * 1e-6;  // 1 bit = 1 µs
    const double fd_us = static_cast<double>(fd_worst_case_duration_ns(s.length, rates)) / 1000.0;
    const double fd = arms * s.rate_hz * fd_us * 1e-6;
    classic_total += classic;
    fd_total += fd;
    o << "| " << s.name << " | " << int(s.length) << " | " << s.rate_hz << " Hz | " << bits << " | "
      << fmt("%.2f %%", 100 * classic) << " | " << fmt("%.1f", fd_us) << " | " << fmt("%.2f %%", 100 * fd) << " |\n";
  }
  o << "| **total** | | | | **" << fmt("%.2f %%", 100 * classic_total) << "** | | **" << fmt("%.2f %%", 100 * fd_total)
    << "** |\n";
  return o.str();
}

}  // namespace

std::vector<std::string> protocol_table_names() { return {"messages", "fields", "parameters", "faults", "bandwidth"}; }

std::string protocol_table(const std::string& name) {
  if (name == "messages") return messages();
  if (name == "fields") return fields_table();
  if (name == "parameters") return parameters();
  if (name == "faults") return faults();
  if (name == "bandwidth") return bandwidth();
  return {};
}

}  // namespace vesica::fp
