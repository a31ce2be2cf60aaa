// Writes the Lua dissector: a data table per message (from message_table.h and the codec probe),
// the codec's cross-field rules with their tables (from protocol_enums.h), and fixed Lua code that
// walks the tables.
#include "firmware_protocol/wireshark/wireshark_dissector.h"

#include <cstdio>
#include <sstream>

#include "firmware_protocol/codec/codec.h"
#include "firmware_protocol/wireshark/codec_probe.h"
#include "firmware_protocol/wireshark/field_bits.h"
#include "firmware_protocol/wireshark/value_names.h"

namespace vesica::fp {
namespace {

namespace F = fields;

std::string lua_string(const char* s) {
  std::string out = "\"";
  for (const char* p = s; *p; ++p) {
    if (*p == '"' || *p == '\\') out += '\\';
    out += *p;
  }
  return out + "\"";
}

std::string number(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);  // round-trips: Lua computes raw * lsb as the codec does
  return buf;
}

std::string hex(unsigned v, int digits) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "0x%0*X", digits, v);
  return buf;
}

// A field is shown in SI units when it has a scale or a unit; counters and enumerations raw.
bool scaled(const FieldSpec& f) { return f.lsb != 1.0 || *f.unit != '\0'; }

// {[2] = "operational", ...} for an enumerated field, else "nil".
std::string value_string(const FieldSpec& f) {
  for (const FieldValueNames& v : field_value_names()) {
    if (v.field != &f) continue;
    std::string out = "{";
    for (std::size_t i = 0; i < v.names.size(); ++i)
      out += (i ? ", [" : "[") + std::to_string(v.names[i].first) + "] = " + lua_string(v.names[i].second.c_str());
    return out + "}";
  }
  return "nil";
}

void write_field(std::ostream& o, const MessageSpec& m, const FieldSpec& f, const CodecProbe& probe) {
  const std::string abbrev = std::string("vesica.") + m.name + "." + f.name;
  const char* int_type = is_signed(f.type) ? "int32" : "uint32";
  o << "      {name = " << lua_string(f.name) << ", offset = " << int(f.offset) << ", size = " << int(wire_size(f.type))
    << ", signed = " << (is_signed(f.type) && f.bit_width == 0 ? "true" : "false") << ", bit_offset = " << int(f.bit_offset)
    << ", bit_width = " << int(f.bit_width) << ", lsb = " << number(f.lsb) << ", unit = " << lua_string(f.unit)
    << ", raw_min = " << raw_min(f) << ", raw_max = " << raw_max(f) << ",\n";
  for (const FieldEnumeration& e : probe.enumerations) {
    if (e.field != &f) continue;
    o << "       valid = {";
    for (std::size_t i = 0; i < e.valid_raw.size(); ++i) o << (i ? ", " : "") << "[" << e.valid_raw[i] << "] = true";
    o << "},\n";
  }
  if (scaled(f)) {
    const std::string label = *f.unit ? std::string(f.name) + " (" + f.unit + ")" : std::string(f.name);
    o << "       pf = ProtoField.double(" << lua_string(abbrev.c_str()) << ", " << lua_string(label.c_str()) << "),\n"
      << "       pf_raw = ProtoField." << int_type << "(" << lua_string((abbrev + ".raw").c_str()) << ", "
      << lua_string((std::string(f.name) + " raw").c_str()) << ")},\n";
  } else {
    const std::string names = value_string(f);
    o << "       pf = ProtoField." << int_type << "(" << lua_string(abbrev.c_str()) << ", " << lua_string(f.name)
      << (names == "nil" ? std::string() : ", base.DEC, " + names) << ")},\n";
  }
}

void write_messages(std::ostream& o) {
  o << "local messages = {\n";
  for (const MessageSpec& m : kMessageSpecs) {
    const CodecProbe probe = probe_codec(m.kind);
    o << "  {name = " << lua_string(m.name) << ", base_id = " << hex(m.base_id, 3) << ", per_node = "
      << (m.per_node ? "true" : "false") << ", length = " << int(m.length) << ", purpose = " << lua_string(m.purpose) << ",\n";
    o << "    fields = {\n";
    for (const FieldSpec* f : kAllFields)
      if (f->message == m.kind) write_field(o, m, *f, probe);
    o << "    },\n    reserved = {";
    for (std::size_t i = 0; i < probe.reserved.size(); ++i)
      o << (i ? ", " : "") << "{offset = " << int(probe.reserved[i].offset) << ", mask = " << hex(probe.reserved[i].mask, 2) << "}";
    o << "},\n  },\n";
  }
  o << "}\n\n";
}

// The codec's Inconsistent rules (codec.cpp); their tables are computed from protocol_enums.h.
void write_consistency(std::ostream& o) {
  o << "-- Cross-field rules the codec checks once every field is in range (DecodeError::Inconsistent).\n";
  o << "local emcy_codes = {";
  for (std::int64_t raw = raw_min(F::Emergency::fault); raw <= raw_max(F::Emergency::fault); ++raw) {
    const auto fault = static_cast<FaultCode>(raw);
    o << (raw ? ", " : "") << "[" << raw << "] = {" << hex(emcy_error_code(fault), 4) << ", " << hex(emcy_error_register(fault), 2) << "}";
  }
  o << "}\n";
  o << "local heartbeat_codes = {";
  for (std::int64_t raw = raw_min(F::Heartbeat::state); raw <= raw_max(F::Heartbeat::state); ++raw)
    o << (raw ? ", " : "") << "[" << raw << "] = " << hex(canopen_heartbeat_code(static_cast<NodeState>(raw)), 2);
  o << "}\n";
  o << "local consistency = {\n"
       "  " << spec_of(MessageKind::Emergency).name << " = function(v)\n"
       "    local c = emcy_codes[v." << F::Emergency::fault.name << "]\n"
       "    if v." << F::Emergency::error_code.name << " ~= c[1] or v." << F::Emergency::error_register.name << " ~= c[2] then\n"
       "      return \"" << F::Emergency::error_code.name << "\", \"error code and register do not match the fault\"\n"
       "    end\n"
       "  end,\n"
       "  " << spec_of(MessageKind::Heartbeat).name << " = function(v)\n"
       "    if v." << F::Heartbeat::canopen_state.name << " ~= heartbeat_codes[v." << F::Heartbeat::state.name << "] then\n"
       "      return \"" << F::Heartbeat::canopen_state.name << "\", \"CANopen state byte does not match the node state\"\n"
       "    end\n"
       "  end,\n"
       "  " << spec_of(MessageKind::Identity).name << " = function(v)\n"
       "    if v." << F::Identity::min_minor.name << " > v." << F::Identity::max_minor.name << " then\n"
       "      return \"" << F::Identity::min_minor.name << "\", \"min_minor is above max_minor\"\n"
       "    end\n"
       "  end,\n"
       "}\n\n";
}

// Fixed code: walks the tables above. Kept to Lua 5.2 without bit operators (Wireshark 3.x/4.x).
constexpr const char* kDissectorCode = R"LUA(local f_message = ProtoField.string("vesica.message", "Message")
local f_node = ProtoField.uint8("vesica.node", "Node id")
local f_error = ProtoField.string("vesica.error", "Malformed")
local f_error_field = ProtoField.string("vesica.error.field", "Malformed field")
local ex_malformed = ProtoExpert.new("vesica.malformed", "Malformed Vesica frame", expert.group.MALFORMED, expert.severity.ERROR)

local all_fields = {f_message, f_node, f_error, f_error_field}
local by_id = {}
for _, m in ipairs(messages) do
  for _, f in ipairs(m.fields) do
    all_fields[#all_fields + 1] = f.pf
    if f.pf_raw then all_fields[#all_fields + 1] = f.pf_raw end
  end
  if m.per_node then
    for node = 1, max_node do by_id[m.base_id + node] = {m, node} end
  else
    by_id[m.base_id] = {m, 0}
  end
end
vesica.fields = all_fields
vesica.experts = {ex_malformed}

local can_id = Field.new("can.id")
local can_rtr = Field.new("can.flags.rtr")

local function read_raw(tvb, f)
  local u = 0
  for i = f.size - 1, 0, -1 do u = u * 256 + tvb(f.offset + i, 1):uint() end
  if f.bit_width > 0 then return math.floor(u / 2 ^ f.bit_offset) % 2 ^ f.bit_width end
  if f.signed and u >= 2 ^ (8 * f.size - 1) then return u - 2 ^ (8 * f.size) end
  return u
end

local function any_bit(byte, mask)
  for bit = 0, 7 do
    local b = 2 ^ bit
    if math.floor(byte / b) % 2 == 1 and math.floor(mask / b) % 2 == 1 then return true end
  end
  return false
end

local function mark(root, item, kind, field, text)
  root:add(f_error, kind):set_generated()
  if field then root:add(f_error_field, field):set_generated() end
  item:add_proto_expert_info(ex_malformed, text)
end

function vesica.dissector(tvb, pinfo, tree)
  local ids = {can_id()}
  if #ids == 0 then return 0 end
  local hit = by_id[ids[#ids].value]
  if not hit then return 0 end
  local m, node = hit[1], hit[2]
  local title = m.per_node and string.format("%s node %d", m.name, node) or m.name
  pinfo.cols.protocol = "Vesica"
  pinfo.cols.info = title
  local root = tree:add(vesica, tvb(), "Vesica " .. title .. ": " .. m.purpose)
  root:add(f_message, m.name):set_generated()
  root:add(f_node, node):set_generated()
  local rtr = {can_rtr()}
  if #rtr > 0 and rtr[#rtr].value then
    mark(root, root, "remote_frame", nil, "remote (RTR) frames are not part of the protocol")
    pinfo.cols.info = title .. " [malformed: remote frame]"
    return tvb:len()
  end
  if tvb:len() ~= m.length then
    mark(root, root, "wrong_length", nil, string.format("%s is %d bytes, not %d", m.name, tvb:len(), m.length))
    pinfo.cols.info = title .. " [malformed: wrong length]"
    return tvb:len()
  end
  local values, bad = {}, nil
  for _, f in ipairs(m.fields) do
    local range = tvb(f.offset, f.size)
    local raw = read_raw(tvb, f)
    values[f.name] = raw
    local item
    if f.pf_raw then
      local si = raw * f.lsb
      item = root:add(f.pf, range, si)
      item:set_text(string.format("%s: %.7g %s (raw %d)", f.name, si, f.unit, raw))
      item:add(f.pf_raw, range, raw)
    else
      item = root:add(f.pf, range, raw)
    end
    if raw < f.raw_min or raw > f.raw_max or (f.valid and not f.valid[raw]) then
      bad = bad or f.name
      local why = (raw < f.raw_min or raw > f.raw_max) and string.format("is outside %d..%d", f.raw_min, f.raw_max)
                  or "is not one of its values"
      mark(root, item, "out_of_range", m.name .. "." .. f.name, string.format("%s = %d %s", f.name, raw, why))
    end
  end
  for _, r in ipairs(m.reserved) do
    local byte = tvb(r.offset, 1):uint()
    if any_bit(byte, r.mask) then
      bad = bad or "reserved"
      mark(root, root, "out_of_range", string.format("%s.reserved%d", m.name, r.offset),
           string.format("byte %d has reserved bits set (mask 0x%02X)", r.offset, r.mask))
    end
  end
  if not bad and consistency[m.name] then
    local field, why = consistency[m.name](values)
    if field then
      bad = field
      mark(root, root, "inconsistent", m.name .. "." .. field, why)
    end
  end
  if bad then pinfo.cols.info = title .. " [malformed: " .. bad .. "]" end
  return tvb:len()
end

local can_ids = DissectorTable.get("can.id")
for id in pairs(by_id) do can_ids:add(id, vesica) end
)LUA";

}  // namespace

std::string wireshark_dissector_lua() {
  std::ostringstream o;
  o << "-- Wireshark dissector for the Vesica haptic-arm CAN protocol " << int(kProtocolMajor) << "." << int(kProtocolMinor)
    << " (docs/protocol.md).\n"
       "-- GENERATED by vesica-wireshark-dissector from firmware_protocol/codec/message_table.h and the codec:\n"
       "-- do not edit. Regenerate: cmake --build build/release --target wireshark_dissector, then copy\n"
       "-- build/release/wireshark/vesica.lua to tools/wireshark/vesica.lua (a test compares the two).\n"
       "-- Load: wireshark -X lua_script:vesica.lua capture.pcap, or copy it into ~/.local/lib/wireshark/plugins/.\n\n"
       "local vesica = Proto(\"vesica\", \"Vesica haptic arm protocol\")\n"
       "local max_node = " << int(kMaxNodeId) << "\n\n";
  write_messages(o);
  write_consistency(o);
  o << kDissectorCode;
  return o.str();
}

}  // namespace vesica::fp
