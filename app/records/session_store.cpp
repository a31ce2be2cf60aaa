#include "app/records/session_store.h"

#include <cmath>
#include <regex>
#include <utility>
#include <variant>

#include "app/records/metric_fields.h"
#include "app/records/postgres_session_store.h"
#include "app/records/session_csv.h"
#include "app/records/sqlite_session_store.h"

namespace vesica::app {

void SessionStore::ExportCsv(const std::string& trainee_id, std::ostream& out) {
  WriteSessionsCsv(List(trainee_id), out);
}

void SessionStore::ValidateForAdd(const SessionRecord& record) const {
  try {
    ValidateRecord(record);
  } catch (const RecordsError& error) {
    throw RecordsError("session database " + Describe() + ": add session: " + error.what());
  }
}

void ValidateRecord(const SessionRecord& record) {
  const auto bad = [&](const std::string& what) {
    throw RecordsError("session record of trainee '" + record.trainee_id + "': " + what);
  };
  if (record.trainee_id.empty()) bad("trainee_id: must not be empty");
  // C strings end at NUL: both backends would store a silently shortened text.
  const std::pair<const char*, const std::string*> texts[] = {{"trainee_id", &record.trainee_id},
                                                              {"scenario", &record.scenario},
                                                              {"station", &record.station},
                                                              {"input_recording_path", &record.input_recording_path}};
  for (const auto& [name, text] : texts) {
    if (text->find('\0') != std::string::npos) bad(std::string(name) + ": contains a NUL character");
  }
  if (record.ended_unix_s < record.started_unix_s) {
    bad("ended_unix_s: " + std::to_string(record.ended_unix_s) + " is before started_unix_s " +
        std::to_string(record.started_unix_s));
  }
  if (!std::isfinite(record.physics_lag_s) || record.physics_lag_s < 0)
    bad("physics_lag_s: must be finite and >= 0, got " + std::to_string(record.physics_lag_s));
  for (const auto& field : kMetricFields) {
    std::visit(
        [&](auto member) {
          const auto value = record.metrics.*member;
          if constexpr (std::is_same_v<decltype(value), const double>) {
            // SQLite would store NaN as NULL; a negative time, length or force is a bug upstream.
            if (!std::isfinite(value) || value < 0) {
              bad(std::string("metrics.") + field.name + ": must be finite and >= 0, got " + std::to_string(value));
            }
          } else if constexpr (std::is_same_v<decltype(value), const int>) {
            if (value < 0) bad(std::string("metrics.") + field.name + ": must be >= 0, got " + std::to_string(value));
          }
        },
        field.member);
  }
}

bool IsConnectionString(const std::string& location) {
  if (location.starts_with("postgresql://") || location.starts_with("postgres://")) return true;
  // libpq keyword=value form: the first word is a lower-case keyword followed by '='.
  static const std::regex keyword_value(R"(^\s*[a-z_]+\s*=)");
  return std::regex_search(location, keyword_value);
}

std::unique_ptr<SessionStore> OpenSessionStore(const std::string& location, StoreAccess access) {
  if (location.empty()) throw RecordsError("session database: empty location");
  // PostgreSQL: reading needs no switch; the server's permissions decide what a role may do.
  if (IsConnectionString(location)) return std::make_unique<PostgresSessionStore>(location);
  return std::make_unique<SqliteSessionStore>(location, access);
}

}  // namespace vesica::app
