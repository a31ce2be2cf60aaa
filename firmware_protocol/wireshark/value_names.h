// Names of the values of enumerated fields (JointState.state 2 -> "operational"), for the
// dissector's display. Names come from the codec's to_string() where it has one, otherwise from a
// switch over the enumeration here, so the compiler (-Wswitch) flags an enumerator added without a
// name. Host side.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "firmware_protocol/codec/message_table.h"

namespace vesica::fp {

struct FieldValueNames {
  const FieldSpec* field = nullptr;
  std::vector<std::pair<std::int64_t, std::string>> names;  // raw value -> name, for every named value in range
};

std::vector<FieldValueNames> field_value_names();

}  // namespace vesica::fp
