// Runs tshark with the generated dissector on a capture and returns one row per frame:
// field abbreviation -> text (several occurrences joined by ',').
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace vesica::fp::test {

using TsharkRow = std::map<std::string, std::string>;

// Throws std::runtime_error with tshark's stderr when it fails (a Lua load error leaves the
// vesica.* fields unknown, which tshark refuses). `work` is a scratch directory.
std::vector<TsharkRow> run_tshark(const std::string& tshark, const std::filesystem::path& capture,
                                  const std::filesystem::path& lua, const std::vector<std::string>& fields,
                                  const std::filesystem::path& work);

}  // namespace vesica::fp::test
