// Random valid protocol frames of a given message kind, and the field values the codec decodes from
// a frame, by field name: what the tshark test compares the dissector's output with.
#pragma once

#include <map>
#include <random>
#include <string>

#include "firmware_protocol/codec/codec.h"

namespace vesica::fp::test {

// A random frame of `kind` that decode() accepts (a random node for per-node messages).
CanFrame random_valid_frame(MessageKind kind, std::mt19937& rng);

// Field name -> value as the codec decoded it (SI for scaled fields, the raw number otherwise);
// empty for a message kind this helper does not know yet.
std::map<std::string, double> codec_field_values(const Message& m);

}  // namespace vesica::fp::test
