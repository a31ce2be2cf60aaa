#include "app/records/pending_sessions.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <type_traits>
#include <variant>
#include <set>
#include <array>
#include <algorithm>

#include "app/records/csv_text.h"
#include "app/records/default_location.h"
#include "app/records/metric_fields.h"

namespace vesica::app {
namespace {

// The columns before the metrics, in the order this build writes them.
constexpr std::array<const char*, 10> kHeadColumns{"trainee_id",   "scenario",   "station",       "started_unix_s",
                                                   "ended_unix_s", "input_recording_path", "replay", "unfinished",
                                                   "physics_lag_s", "procedure"};

std::string Header() {
  std::string header;
  for (const char* column : kHeadColumns) {
    if (!header.empty()) header += ',';
    header += column;
  }
  for (const auto& field : kMetricFields) header += std::string(",") + field.name;
  return header + "\n";
}

std::string Row(const SessionRecord& r) {
  std::string row = CsvField(r.trainee_id) + "," + CsvField(r.scenario) + "," + CsvField(r.station) + "," +
                    std::to_string(r.started_unix_s) + "," + std::to_string(r.ended_unix_s) + "," +
                    CsvField(r.input_recording_path) + "," + (r.replay ? "1" : "0") + "," + (r.unfinished ? "1" : "0") +
                    "," + ShortestDoubleText(r.physics_lag_s) + "," + ProcedureKey(r.procedure);
  for (const auto& field : kMetricFields) {
    row += ",";
    std::visit(
        [&](auto member) {
          using T = std::remove_cvref_t<decltype(r.metrics.*member)>;
          if constexpr (std::is_same_v<T, double>)
            row += ShortestDoubleText(r.metrics.*member);
          else if constexpr (std::is_same_v<T, bool>)
            row += r.metrics.*member ? "1" : "0";
          else
            row += std::to_string(r.metrics.*member);
        },
        field.member);
  }
  return row + "\n";
}

// RFC 4180 rows with the line each starts on.
std::vector<std::pair<int, std::vector<std::string>>> ParseCsv(const std::string& text) {
  std::vector<std::pair<int, std::vector<std::string>>> rows;
  std::vector<std::string> row;
  std::string field;
  bool quoted = false;
  int line = 1, row_line = 1;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (quoted) {
      if (c == '"' && i + 1 < text.size() && text[i + 1] == '"') {
        field += '"';
        ++i;
      } else if (c == '"') {
        quoted = false;
      } else {
        if (c == '\n') ++line;
        field += c;
      }
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      row.push_back(std::move(field));
      field.clear();
    } else if (c == '\n') {
      row.push_back(std::move(field));
      field.clear();
      rows.emplace_back(row_line, std::move(row));
      row.clear();
      row_line = ++line;
    } else {
      field += c;
    }
  }
  // A row cut short (the trainer killed while appending) is dropped: it was never promised.
  return rows;
}

template <typename T>
T Number(const std::string& text, const std::string& where, const char* name) {
  T value{};
  const auto [ptr, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || ptr != text.data() + text.size() || text.empty())
    throw RecordsError(where + ": " + name + ": not a number: '" + text + "'");
  return value;
}

bool Flag(const std::string& text, const std::string& where, const char* name) {
  if (text != "0" && text != "1") throw RecordsError(where + ": " + name + ": not 0 or 1: '" + text + "'");
  return text == "1";
}

// A row read by the names in the file's own header: a file an older build left (fewer columns,
// schema 2) reads with the missing ones at their defaults; an unknown or repeated column is an error.
SessionRecord ParseRow(const std::vector<std::string>& header, const std::vector<std::string>& f,
                       const std::string& where) {
  if (f.size() != header.size())
    throw RecordsError(where + ": " + std::to_string(f.size()) + " fields, expected " + std::to_string(header.size()));
  SessionRecord r;
  for (std::size_t i = 0; i < header.size(); ++i) {
    const std::string& name = header[i];
    const std::string& text = f[i];
    if (name == "trainee_id") {
      r.trainee_id = text;
    } else if (name == "scenario") {
      r.scenario = text;
    } else if (name == "station") {
      r.station = text;
    } else if (name == "started_unix_s") {
      r.started_unix_s = Number<std::int64_t>(text, where, "started_unix_s");
    } else if (name == "ended_unix_s") {
      r.ended_unix_s = Number<std::int64_t>(text, where, "ended_unix_s");
    } else if (name == "input_recording_path") {
      r.input_recording_path = text;
    } else if (name == "replay") {
      r.replay = Flag(text, where, "replay");
    } else if (name == "unfinished") {
      r.unfinished = Flag(text, where, "unfinished");
    } else if (name == "physics_lag_s") {
      r.physics_lag_s = Number<double>(text, where, "physics_lag_s");
    } else if (name == "procedure") {
      const auto procedure = ParseProcedure(text);
      if (!procedure) throw RecordsError(where + ": procedure: unknown procedure '" + text + "'");
      r.procedure = *procedure;
    } else {
      const auto field = std::find_if(kMetricFields.begin(), kMetricFields.end(),
                                      [&](const MetricField& candidate) { return name == candidate.name; });
      if (field == kMetricFields.end()) throw RecordsError(where + ": unknown column '" + name + "'");
      std::visit(
          [&](auto member) {
            using T = std::remove_cvref_t<decltype(r.metrics.*member)>;
            if constexpr (std::is_same_v<T, bool>)
              r.metrics.*member = Flag(text, where, field->name);
            else
              r.metrics.*member = Number<T>(text, where, field->name);
          },
          field->member);
    }
  }
  return r;
}

// The header row's columns, checked: every one known, none twice, trainee_id first.
std::vector<std::string> ParseHeader(const std::vector<std::string>& header, const std::string& where) {
  if (header.empty() || header[0] != "trainee_id") throw RecordsError(where + ": no header row");
  std::set<std::string> seen;
  for (const std::string& name : header) {
    if (!seen.insert(name).second) throw RecordsError(where + ": column '" + name + "' appears twice");
  }
  return header;
}

[[noreturn]] void Fail(const std::filesystem::path& path, const std::string& what) {
  throw RecordsError("pending sessions file " + path.string() + ": " + what + ": " + std::strerror(errno));
}

// Writes `text` to `path` through a temporary file, synced and renamed over it.
void ReplaceFile(const std::filesystem::path& path, const std::string& text) {
  const std::string temporary = path.string() + ".tmp";
  const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) Fail(path, "cannot rewrite");
  const bool ok = ::write(fd, text.data(), text.size()) == static_cast<ssize_t>(text.size()) && ::fsync(fd) == 0;
  const int saved = errno;
  ::close(fd);
  errno = saved;
  if (!ok || std::rename(temporary.c_str(), path.c_str()) != 0) {
    const int reason = errno;
    ::unlink(temporary.c_str());
    errno = reason;
    Fail(path, "cannot rewrite");
  }
}

std::string FirstLine(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::string line;
  std::getline(in, line);
  return line;
}

}  // namespace

// A file an older build left has other columns: its sessions are rewritten in this build's
// columns before a row is appended, so that every row of the file follows its header. A file
// that does not read is moved aside (kept for a person to look at), never overwritten.
void RewriteInThisBuildsColumns(const std::filesystem::path& path) {
  std::error_code error;
  if (!std::filesystem::exists(path, error) || std::filesystem::file_size(path, error) == 0) return;
  const std::string header = Header();
  if (FirstLine(path) + "\n" == header) return;
  std::string text = header;
  try {
    for (const SessionRecord& old : ReadPendingSessions(path)) text += Row(old);
  } catch (const RecordsError&) {
    const std::filesystem::path aside = path.string() + ".unreadable";
    if (std::rename(path.c_str(), aside.c_str()) != 0) Fail(path, "cannot move the unreadable file aside");
    return;
  }
  ReplaceFile(path, text);
}

std::filesystem::path PendingSessionsPath(const std::string& location) {
  if (IsConnectionString(location)) {
    return DefaultSessionDatabasePath([](const char* name) { return std::getenv(name); }).parent_path() /
           "pending-sessions.csv";
  }
  return location + ".pending.csv";
}

void KeepPendingSession(const std::filesystem::path& path, const SessionRecord& record) {
  std::error_code error;
  if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path(), error);
  if (error) {
    errno = error.value();
    Fail(path, "cannot create its folder");
  }
  RewriteInThisBuildsColumns(path);
  const int fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
  if (fd < 0) Fail(path, "cannot open");
  // A row cut short by a kill was never promised: cut it off so this one starts on its own line.
  off_t end = ::lseek(fd, 0, SEEK_END);
  for (char c = 0; end > 0 && ::pread(fd, &c, 1, end - 1) == 1 && c != '\n';) --end;
  if (end != ::lseek(fd, 0, SEEK_END) && ::ftruncate(fd, end) != 0) {
    const int saved = errno;
    ::close(fd);
    errno = saved;
    Fail(path, "cannot repair");
  }
  const bool empty = end == 0;
  const std::string text = (empty ? Header() : "") + Row(record);
  const bool ok = ::write(fd, text.data(), text.size()) == static_cast<ssize_t>(text.size()) && ::fsync(fd) == 0;
  const int saved = errno;
  ::close(fd);
  errno = saved;
  if (!ok) Fail(path, "cannot write");
}

std::vector<SessionRecord> ReadPendingSessions(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    if (!std::filesystem::exists(path)) return {};
    Fail(path, "cannot read");
  }
  std::stringstream text;
  text << in.rdbuf();
  std::vector<SessionRecord> records;
  const auto rows = ParseCsv(text.str());
  std::vector<std::string> header;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const std::string where = "pending sessions file " + path.string() + ":" + std::to_string(rows[i].first);
    if (i == 0) {
      header = ParseHeader(rows[i].second, where);
      continue;
    }
    records.push_back(ParseRow(header, rows[i].second, where));
  }
  return records;
}

PendingStoreResult StorePendingSessions(const std::filesystem::path& path, SessionStore& store) {
  PendingStoreResult result;
  const std::vector<SessionRecord> pending = ReadPendingSessions(path);
  if (pending.empty()) return result;
  std::string left;
  for (const SessionRecord& record : pending) {
    try {
      store.Add(record);
      ++result.stored;
    } catch (const RecordsError& e) {
      if (result.error.empty()) result.error = e.what();
      ++result.left;
      left += Row(record);
    }
  }
  if (result.left == 0) {
    if (std::remove(path.c_str()) != 0) Fail(path, "cannot remove");
  } else {
    ReplaceFile(path, Header() + left);
  }
  return result;
}

}  // namespace vesica::app
