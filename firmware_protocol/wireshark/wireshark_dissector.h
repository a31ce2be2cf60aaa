// A Wireshark dissector (Lua) for the Vesica CAN protocol, generated from the one definition of the
// wire format (message_table.h) and from the codec itself (codec_probe.h), so it cannot drift.
// It registers in Wireshark's "can.id" table for every identifier of the plan and shows each frame
// as message name, node id and every field (SI value with unit, and raw); frames the codec would
// refuse are marked malformed: vesica.error is the codec's DecodeError name (remote_frame,
// wrong_length, out_of_range, inconsistent), vesica.error.field the field at fault.
// Use: wireshark_dissector_lua() -> the file's text (the program vesica-wireshark-dissector writes
// it; tools/wireshark/vesica.lua is the committed copy). Host side.
#pragma once

#include <string>

namespace vesica::fp {

std::string wireshark_dissector_lua();

}  // namespace vesica::fp
