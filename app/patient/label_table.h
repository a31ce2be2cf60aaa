#pragma once
// The label table (TOML) that says which value of a label map is which structure, e.g.
//   [[label]]
//   value = 10
//   name = "liver"
// Names are those of label_names.cpp (liver, diaphragm_tendon, rib_r7, ...). A real segmentation
// (ITK-SNAP numbers its labels 1, 2, ...) is read through its own table and remapped to the
// trainer's values.

#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace vesica::app::patient {

struct LabelEntry {
  int value = 0;     ///< in the file's label map, 0-255
  std::string name;  ///< the structure
};
using LabelTable = std::vector<LabelEntry>;

/// The trainer's value (physics::patient_label) for a structure name, or nothing if unknown.
[[nodiscard]] std::optional<std::uint8_t> LabelValueOfName(const std::string& name);
/// The name of a trainer label value ("" if none).
[[nodiscard]] std::string NameOfLabelValue(std::uint8_t value);
/// The trainer's own table: every structure it knows, by its own values.
[[nodiscard]] LabelTable TrainerLabelTable();

/// Reads a table. Throws std::runtime_error naming the file (and the entry) for a parse error, a
/// value outside 0-255, a value given twice, or an unknown name.
[[nodiscard]] LabelTable ReadLabelTable(const std::filesystem::path& file);
void WriteLabelTable(const LabelTable& table, const std::filesystem::path& file, const std::string& comment);

/// file value -> trainer value, for every entry of the table.
[[nodiscard]] std::map<int, std::uint8_t> RemapToTrainer(const LabelTable& table);

}  // namespace vesica::app::patient
