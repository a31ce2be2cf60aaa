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

#include "app/records/csv_text.h"
#include "app/records/default_location.h"
#include "app/records/metric_fields.h"

namespace vesica::app {
namespace {

constexpr int kHeadFields = 9;  // trainee_id ... physics_lag_s

std::string Header() {
  std::string header =
      "trainee_id,scenario,station,started_unix_s,ended_unix_s,input_recording_path,replay,unfinished,physics_lag_s";
  for (const auto& field : kMetricFields) header += std::string(",") + field.name;
  return header + "\n";
}



std::string Row(const SessionRecord& r) {
  std::string row = CsvField(r.trainee_id) + "," + CsvField(r.scenario) + "," + CsvField(r.station) + "," +
                    std::to_string(r.started_unix_s) + "," + std::to_string(r.ended_unix_s) + "," +
                    CsvField(r.input_recording_path) + "," + (r.replay ? "1" : "0") + "," + (r.unfinished ? "1" : "0") +
                    "," + ShortestDoubleText(r.physics_lag_s);
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

SessionRecord ParseRow(const std::vector<std::string>& f, const std::string& where) {
  const std::size_t expected = kHeadFields + kMetricFields.size();
  if (f.size() != expected)
    throw RecordsError(where + ": " + std::to_string(f.size()) + " fields, expected " + std::to_string(expected));
  SessionRecord r;
  r.trainee_id = f[0];
  r.scenario = f[1];
  r.station = f[2];
  r.started_unix_s = Number<std::int64_t>(f[3], where, "started_unix_s");
  r.ended_unix_s = Number<std::int64_t>(f[4], where, "ended_unix_s");
  r.input_recording_path = f[5];
  r.replay = Flag(f[6], where, "replay");
  r.unfinished = Flag(f[7], where, "unfinished");
  r.physics_lag_s = Number<double>(f[8], where, "physics_lag_s");
  std::size_t i = kHeadFields;
  for (const auto& field : kMetricFields) {
    std::visit(
        [&](auto member) {
          using T = std::remove_cvref_t<decltype(r.metrics.*member)>;
          if constexpr (std::is_same_v<T, bool>)
            r.metrics.*member = Flag(f[i], where, field.name);
          else
            r.metrics.*member = Number<T>(f[i], where, field.name);
        },
        field.member);
    ++i;
  }
  return r;
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

}  // namespace

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
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const std::string where = "pending sessions file " + path.string() + ":" + std::to_string(rows[i].first);
    if (i == 0) {
      if (rows[i].second.empty() || rows[i].second[0] != "trainee_id") throw RecordsError(where + ": no header row");
      continue;
    }
    records.push_back(ParseRow(rows[i].second, where));
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
