#include "app/patient/label_table.h"

#include <toml++/toml.h>

#include <algorithm>
#include <fstream>
#include <set>
#include <sstream>
#include <stdexcept>

#include "physics/patient/patient_labels.h"

namespace vesica::app::patient {
namespace label = physics::patient_label;
namespace {

const std::map<std::string, std::uint8_t>& NameToValue() {
  static const std::map<std::string, std::uint8_t> table = [] {
    std::map<std::string, std::uint8_t> t = {
        {"air", label::kAir},
        {"skin", label::kSkin},
        {"subcutaneous_fat", label::kFat},
        {"muscle", label::kMuscle},
        {"spine", label::kSpine},
        {"sternum", label::kSternum},
        {"lung", label::kLung},
        {"costophrenic_recess", label::kCostophrenicRecess},
        {"diaphragm_muscle", label::kDiaphragmMuscle},
        {"diaphragm_tendon", label::kDiaphragmTendon},
        {"liver", label::kLiver},
        {"liver_capsule", label::kLiverCapsule},
        {"tumour", label::kTumour},
        {"gallbladder", label::kGallbladder},
        {"colon", label::kColon},
        {"soft_tissue", label::kSoftTissue},
    };
    for (int side = 0; side < 2; ++side)
      for (int n = 1; n <= label::kMaxRib; ++n) {
        const bool left = side == 1;
        const std::string suffix = std::string(left ? "_l" : "_r") + std::to_string(n);
        t["rib" + suffix] = label::Rib(left, n);
        t["costal_cartilage" + suffix] = label::Cartilage(left, n);
        t["intercostal_bundle" + suffix] = label::Bundle(left, n);
      }
    return t;
  }();
  return table;
}

}  // namespace

std::optional<std::uint8_t> LabelValueOfName(const std::string& name) {
  const auto it = NameToValue().find(name);
  if (it == NameToValue().end()) return std::nullopt;
  return it->second;
}

std::string NameOfLabelValue(std::uint8_t value) {
  for (const auto& [name, v] : NameToValue())
    if (v == value) return name;
  return "";
}

LabelTable TrainerLabelTable() {
  LabelTable table;
  for (const auto& [name, value] : NameToValue()) table.push_back({value, name});
  std::sort(table.begin(), table.end(), [](const LabelEntry& a, const LabelEntry& b) { return a.value < b.value; });
  return table;
}

LabelTable ReadLabelTable(const std::filesystem::path& file) {
  const std::string where = "label table " + file.string();
  toml::table root;
  try {
    root = toml::parse_file(file.string());
  } catch (const toml::parse_error& e) {
    std::ostringstream message;
    message << where << ": " << e.description() << " (line " << e.source().begin.line << ")";
    throw std::runtime_error(message.str());
  }
  const toml::array* entries = root["label"].as_array();
  if (!entries || entries->empty()) throw std::runtime_error(where + ": no [[label]] entries");
  LabelTable table;
  std::set<int> seen;
  for (std::size_t e = 0; e < entries->size(); ++e) {
    const toml::table* entry = (*entries)[e].as_table();
    const std::string at = where + ", label entry " + std::to_string(e + 1);
    if (!entry) throw std::runtime_error(at + ": not a table");
    const auto value = (*entry)["value"].value<std::int64_t>();
    const auto name = (*entry)["name"].value<std::string>();
    if (!value || !name) throw std::runtime_error(at + ": needs an integer 'value' and a string 'name'");
    if (*value < 0 || *value > 255)
      throw std::runtime_error(at + ": value " + std::to_string(*value) + " is outside 0-255");
    if (!seen.insert(static_cast<int>(*value)).second)
      throw std::runtime_error(at + ": value " + std::to_string(*value) + " is given twice");
    if (!LabelValueOfName(*name)) throw std::runtime_error(at + ": unknown structure name '" + *name + "'");
    table.push_back({static_cast<int>(*value), *name});
  }
  return table;
}

void WriteLabelTable(const LabelTable& table, const std::filesystem::path& file, const std::string& comment) {
  std::ofstream out(file);
  if (!out) throw std::runtime_error("cannot write label table " + file.string());
  std::istringstream lines(comment);
  for (std::string line; std::getline(lines, line);) out << "# " << line << "\n";
  for (const LabelEntry& e : table) out << "\n[[label]]\nvalue = " << e.value << "\nname = \"" << e.name << "\"\n";
  if (!out) throw std::runtime_error("cannot write label table " + file.string());
}

std::map<int, std::uint8_t> RemapToTrainer(const LabelTable& table) {
  std::map<int, std::uint8_t> remap;
  for (const LabelEntry& e : table) remap[e.value] = *LabelValueOfName(e.name);
  return remap;
}

}  // namespace vesica::app::patient
