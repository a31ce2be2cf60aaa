#pragma once
// A 64-bit FNV-1a digest of everything a session's outcome consists of (organ shapes, burn maps,
// membrane health, springs): two runs with equal digests ended in bit-identical states.

#include <cstdint>
#include <string>

#include "app/session/dissection_session.h"

namespace vesica::app {

std::uint64_t StateDigest(const DissectionSession& session);
/// 16 lowercase hex digits.
std::string FormatDigest(std::uint64_t digest);

}  // namespace vesica::app
