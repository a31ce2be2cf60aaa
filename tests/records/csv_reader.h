#pragma once
// A small RFC 4180 reader for checking exports: quoted fields may hold commas, doubled quotes
// and line breaks. Test-only; the product writes CSV, never reads it.

#include <stdexcept>
#include <string>
#include <vector>

namespace vesica::app::testing {

inline std::vector<std::vector<std::string>> ReadCsv(const std::string& text) {
  std::vector<std::vector<std::string>> rows;
  std::vector<std::string> row;
  std::string field;
  bool quoted = false, field_started = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (quoted) {
      if (c == '"' && i + 1 < text.size() && text[i + 1] == '"') {
        field += '"';
        ++i;
      } else if (c == '"') {
        quoted = false;
      } else {
        field += c;
      }
    } else if (c == '"') {
      if (field_started) throw std::runtime_error("quote inside an unquoted field at byte " + std::to_string(i));
      quoted = field_started = true;
    } else if (c == ',') {
      row.push_back(field);
      field.clear();
      field_started = false;
    } else if (c == '\n') {
      row.push_back(field);
      rows.push_back(row);
      row.clear();
      field.clear();
      field_started = false;
    } else {
      field += c;
      field_started = true;
    }
  }
  if (quoted) throw std::runtime_error("unterminated quoted field");
  if (field_started || !row.empty()) throw std::runtime_error("last row not terminated by a line break");
  return rows;
}

}  // namespace vesica::app::testing
