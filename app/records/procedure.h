#pragma once
// Which operation a session trained. Stored as its key ("cholecystectomy", "needle_biopsy") in
// the sessions table (schema version 3), the CSV export and the pending file.

#include <optional>
#include <string_view>

namespace vesica::app {

enum class Procedure { kCholecystectomy, kNeedleBiopsy };

/// The stored key: "cholecystectomy" or "needle_biopsy".
constexpr const char* ProcedureKey(Procedure procedure) {
  return procedure == Procedure::kNeedleBiopsy ? "needle_biopsy" : "cholecystectomy";
}

/// What a person reads: "Cholecystectomy" or "Needle biopsy".
constexpr const char* ProcedureTitle(Procedure procedure) {
  return procedure == Procedure::kNeedleBiopsy ? "Needle biopsy" : "Cholecystectomy";
}

/// The procedure of a stored key; nullopt for anything else.
constexpr std::optional<Procedure> ParseProcedure(std::string_view key) {
  if (key == ProcedureKey(Procedure::kCholecystectomy)) return Procedure::kCholecystectomy;
  if (key == ProcedureKey(Procedure::kNeedleBiopsy)) return Procedure::kNeedleBiopsy;
  return std::nullopt;
}

}  // namespace vesica::app
