// Markdown tables of docs/protocol.md, generated from the one definition of the wire format
// (message_table.h, parameter_table.h, protocol_enums.h, frame_timing.h).
// Use: protocol_table("messages") -> the text between the doc's
//   <!-- BEGIN GENERATED: messages --> and <!-- END GENERATED: messages --> markers.
// A test (tests/can/protocol_doc_test.cpp) checks the document against these; the program
// can_print_protocol_tables prints them for pasting. Host only (std::string).
#pragma once

#include <string>
#include <vector>

namespace vesica::fp {

std::vector<std::string> protocol_table_names();  // messages, fields, parameters, faults, bandwidth
std::string protocol_table(const std::string& name);  // empty for an unknown name

}  // namespace vesica::fp
