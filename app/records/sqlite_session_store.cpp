#include "app/records/sqlite_session_store.h"

#include <sqlite3.h>

#include <cstdio>
#include <system_error>
#include <variant>

#include "app/records/metric_fields.h"
#include "app/records/sql_schema.h"

namespace vesica::app {
namespace {

struct StatementDeleter {
  void operator()(sqlite3_stmt* statement) const { sqlite3_finalize(statement); }
};
using Statement = std::unique_ptr<sqlite3_stmt, StatementDeleter>;

}  // namespace

// The connection, and the error path every call shares: "session database PATH: STEP: sqlite says".
namespace detail {
struct SqliteDb {
  std::string location;
  sqlite3* handle = nullptr;
  bool read_only = false;
  int schema_version = 0;  // as opened (read-only stores read older schemas as they are)

  ~SqliteDb() {
    if (handle != nullptr) sqlite3_close_v2(handle);
  }

  [[noreturn]] void Fail(const std::string& step) const {
    const std::string reason = handle != nullptr ? sqlite3_errmsg(handle) : "out of memory";
    throw RecordsError("session database " + location + ": " + step + ": " + reason);
  }

  void Check(int rc, const std::string& step) const {
    if (rc != SQLITE_OK && rc != SQLITE_DONE && rc != SQLITE_ROW) Fail(step);
  }

  Statement Prepare(const std::string& sql, const std::string& step) const {
    sqlite3_stmt* statement = nullptr;
    Check(sqlite3_prepare_v2(handle, sql.c_str(), static_cast<int>(sql.size()), &statement, nullptr), step);
    return Statement(statement);
  }

  void Exec(const std::string& sql, const std::string& step) const {
    Check(sqlite3_exec(handle, sql.c_str(), nullptr, nullptr, nullptr), step);
  }

  // First column of the first row as text (PRAGMA results); "" when there is no row.
  std::string QueryText(const std::string& sql, const std::string& step) const {
    auto statement = Prepare(sql, step);
    const int rc = sqlite3_step(statement.get());
    Check(rc, step);
    if (rc != SQLITE_ROW) return "";
    const auto* text = sqlite3_column_text(statement.get(), 0);
    return text != nullptr ? reinterpret_cast<const char*>(text) : "";
  }

  // All rows' first column joined by "; " (integrity_check lists one problem a row).
  std::string QueryAllText(const std::string& sql, const std::string& step) const {
    auto statement = Prepare(sql, step);
    std::string joined;
    for (int rc = sqlite3_step(statement.get()); rc != SQLITE_DONE; rc = sqlite3_step(statement.get())) {
      Check(rc, step);
      const auto* text = sqlite3_column_text(statement.get(), 0);
      joined += (joined.empty() ? "" : "; ") + std::string(text != nullptr ? reinterpret_cast<const char*>(text) : "");
    }
    return joined;
  }
};
}  // namespace detail

namespace {

// Rolls back unless committed, so an exception between BEGIN and COMMIT leaves nothing behind.
class Transaction {
 public:
  Transaction(const detail::SqliteDb& db, const std::string& step) : db_(db) {
    // IMMEDIATE takes the write lock now, so a concurrent writer waits (busy_timeout) here
    // instead of failing halfway through.
    db_.Exec("BEGIN IMMEDIATE", step + ": begin");
  }
  ~Transaction() {
    if (!committed_) sqlite3_exec(db_.handle, "ROLLBACK", nullptr, nullptr, nullptr);
  }
  void Commit(const std::string& step) {
    db_.Exec("COMMIT", step + ": commit");
    committed_ = true;
  }

 private:
  const detail::SqliteDb& db_;
  bool committed_ = false;
};

// A file path as the path part of an SQLite URI: '%', '?' and '#' escaped (and an absolute path
// kept absolute), so that any file name opens.
std::string UriPath(const std::string& path) {
  std::string uri;
  for (const char c : path) {
    if (c == '%' || c == '?' || c == '#') {
      char escaped[4];
      std::snprintf(escaped, sizeof escaped, "%%%02X", static_cast<unsigned char>(c));
      uri += escaped;
    } else {
      uri += c;
    }
  }
  return uri;
}

std::string ColumnText(sqlite3_stmt* statement, int column) {
  const auto* text = sqlite3_column_text(statement, column);
  return text != nullptr ? reinterpret_cast<const char*>(text) : "";
}

StoredSession ReadSessionRow(sqlite3_stmt* statement) {
  StoredSession session;
  session.id = sqlite3_column_int64(statement, 0);
  auto& r = session.record;
  r.trainee_id = ColumnText(statement, 1);
  r.scenario = ColumnText(statement, 2);
  r.station = ColumnText(statement, 3);
  r.started_unix_s = sqlite3_column_int64(statement, 4);
  r.ended_unix_s = sqlite3_column_int64(statement, 5);
  r.input_recording_path = ColumnText(statement, 6);
  r.replay = sqlite3_column_int(statement, 7) != 0;
  r.unfinished = sqlite3_column_int(statement, 8) != 0;
  r.physics_lag_s = sqlite3_column_double(statement, 9);
  // The CHECK constraint keeps anything else out of a store this build wrote.
  r.procedure = ParseProcedure(ColumnText(statement, 10)).value_or(Procedure::kCholecystectomy);
  int column = kSessionHeadColumns;
  for (const auto& field : kMetricFields) {
    std::visit(
        [&](auto member) {
          using T = std::remove_cvref_t<decltype(r.metrics.*member)>;
          if constexpr (std::is_same_v<T, double>)
            r.metrics.*member = sqlite3_column_double(statement, column);
          else if constexpr (std::is_same_v<T, int>)
            r.metrics.*member = sqlite3_column_int(statement, column);
          else
            r.metrics.*member = sqlite3_column_int(statement, column) != 0;
        },
        field.member);
    ++column;
  }
  return session;
}

}  // namespace

SqliteSessionStore::SqliteSessionStore(const std::filesystem::path& path, StoreAccess access)
    : db_(std::make_unique<detail::SqliteDb>()) {
  db_->location = path.string();
  db_->read_only = access == StoreAccess::kReadOnly;
  const auto throw_here = [&](const std::string& what) {
    throw RecordsError("session database " + db_->location + ": " + what);
  };
  if (db_->read_only) {
    std::error_code error;
    if (!std::filesystem::exists(path, error)) throw_here("no such file (no session recorded there)");
  } else if (path.has_parent_path()) {
    std::error_code error;
    std::filesystem::create_directories(path.parent_path(), error);
    if (error) throw_here("cannot create folder " + path.parent_path().string() + ": " + error.message());
  }
  if (std::filesystem::is_directory(path)) throw_here("is a directory, not a database file");

  if (db_->read_only) {
    OpenReadOnly();
  } else {
    OpenReadWrite();
  }
}

void SqliteSessionStore::OpenReadOnly() {
  const auto throw_here = [&](const std::string& what) {
    throw RecordsError("session database " + db_->location + ": " + what);
  };
  // A WAL database in a folder we cannot write (no -shm to create) opens read-only only as
  // "immutable": then SQLite reads the main file as it is and takes no locks.
  for (const char* extra : {"", "&immutable=1"}) {
    if (db_->handle != nullptr) sqlite3_close_v2(db_->handle);
    db_->handle = nullptr;
    const std::string uri = "file:" + UriPath(db_->location) + "?mode=ro" + extra;
    if (sqlite3_open_v2(uri.c_str(), &db_->handle, SQLITE_OPEN_READONLY | SQLITE_OPEN_URI | SQLITE_OPEN_FULLMUTEX,
                        nullptr) != SQLITE_OK)
      db_->Fail("open read-only");
    sqlite3_extended_result_codes(db_->handle, 1);
    db_->Check(sqlite3_busy_timeout(db_->handle, 5000), "set busy timeout");
    sqlite3_stmt* probe = nullptr;
    int rc = sqlite3_prepare_v2(db_->handle, "PRAGMA user_version", -1, &probe, nullptr);
    if (rc == SQLITE_OK) rc = sqlite3_step(probe);
    sqlite3_finalize(probe);
    const int primary = rc & 0xff;
    if (primary != SQLITE_READONLY && primary != SQLITE_CANTOPEN) break;  // other errors: reported below
  }
  const std::string check = db_->QueryAllText("PRAGMA quick_check", "check database");
  if (check != "ok") throw_here("database is corrupt (quick_check: " + check + ")");
  db_->schema_version = SchemaVersion();
  if (db_->schema_version > kSessionSchemaVersion) {
    throw_here("schema version " + std::to_string(db_->schema_version) +
               " was written by a newer Vesica (this build knows up to " + std::to_string(kSessionSchemaVersion) + ")");
  }
}

void SqliteSessionStore::OpenReadWrite() {
  const auto throw_here = [&](const std::string& what) {
    throw RecordsError("session database " + db_->location + ": " + what);
  };
  const int flags = SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE | SQLITE_OPEN_FULLMUTEX;
  if (sqlite3_open_v2(db_->location.c_str(), &db_->handle, flags, nullptr) != SQLITE_OK) db_->Fail("open");
  sqlite3_extended_result_codes(db_->handle, 1);
  // Another process (the CLI, a second trainer) may hold the lock briefly: wait for it.
  db_->Check(sqlite3_busy_timeout(db_->handle, 5000), "set busy timeout");

  // The first statements read the header: a file that is not SQLite fails here.
  const std::string mode = db_->QueryText("PRAGMA journal_mode=WAL", "switch to WAL journal");
  if (mode != "wal") throw_here("switch to WAL journal: SQLite kept journal mode '" + mode + "'");
  // FULL also survives power loss, not only a killed process; one fsync per session is cheap.
  db_->Exec("PRAGMA synchronous=FULL", "set synchronous=FULL");
  db_->Exec("PRAGMA foreign_keys=ON", "enable foreign keys");
  const std::string check = db_->QueryAllText("PRAGMA quick_check", "check database");
  if (check != "ok") throw_here("database is corrupt (quick_check: " + check + ")");

  int version = SchemaVersion();
  if (version > kSessionSchemaVersion) {
    throw_here("schema version " + std::to_string(version) + " was written by a newer Vesica (this build knows up to " +
               std::to_string(kSessionSchemaVersion) + ")");
  }
  if (version < kSessionSchemaVersion) {
    const std::string step =
        "migrate schema " + std::to_string(version) + " -> " + std::to_string(kSessionSchemaVersion);
    Transaction transaction(*db_, step);
    version = SchemaVersion();  // another process may have migrated while we waited for the lock
    if (version == 0) {
      for (const auto& sql : CreateSchemaV1Sql(SqlDialect::kSqlite)) db_->Exec(sql, step);
      version = 1;
    }
    if (version == 1) {
      for (const auto& sql : MigrateSchemaV1ToV2Sql(SqlDialect::kSqlite)) db_->Exec(sql, step);
      version = 2;
    }
    if (version == 2) {
      for (const auto& sql : MigrateSchemaV2ToV3Sql(SqlDialect::kSqlite)) db_->Exec(sql, step);
      version = 3;
    }
    if (version == 3) {
      for (const auto& sql : MigrateSchemaV3ToV4Sql(SqlDialect::kSqlite)) db_->Exec(sql, step);
    }
    db_->Exec("PRAGMA user_version=" + std::to_string(kSessionSchemaVersion), step);
    transaction.Commit(step);
  }
  db_->schema_version = kSessionSchemaVersion;
}

SqliteSessionStore::~SqliteSessionStore() = default;

std::int64_t SqliteSessionStore::Add(const SessionRecord& record) {
  if (db_->read_only) throw RecordsError("session database " + db_->location + ": add session: opened read-only");
  ValidateForAdd(record);
  const std::string step = "add session of trainee '" + record.trainee_id + "'";
  Transaction transaction(*db_, step);

  auto trainee = db_->Prepare(InsertTraineeSql(SqlDialect::kSqlite), step);
  db_->Check(sqlite3_bind_text(trainee.get(), 1, record.trainee_id.c_str(), -1, SQLITE_TRANSIENT), step);
  db_->Check(sqlite3_step(trainee.get()), step);

  auto insert = db_->Prepare(InsertSessionSql(SqlDialect::kSqlite), step);
  sqlite3_stmt* s = insert.get();
  int index = 1;
  for (const std::string* text : {&record.trainee_id, &record.scenario, &record.station}) {
    db_->Check(sqlite3_bind_text(s, index++, text->c_str(), -1, SQLITE_TRANSIENT), step);
  }
  db_->Check(sqlite3_bind_int64(s, index++, record.started_unix_s), step);
  db_->Check(sqlite3_bind_int64(s, index++, record.ended_unix_s), step);
  db_->Check(sqlite3_bind_text(s, index++, record.input_recording_path.c_str(), -1, SQLITE_TRANSIENT), step);
  db_->Check(sqlite3_bind_int(s, index++, record.replay ? 1 : 0), step);
  db_->Check(sqlite3_bind_int(s, index++, record.unfinished ? 1 : 0), step);
  db_->Check(sqlite3_bind_double(s, index++, record.physics_lag_s), step);
  db_->Check(sqlite3_bind_text(s, index++, ProcedureKey(record.procedure), -1, SQLITE_STATIC), step);
  for (const auto& field : kMetricFields) {
    std::visit(
        [&](auto member) {
          using T = std::remove_cvref_t<decltype(record.metrics.*member)>;
          const T value = record.metrics.*member;
          if constexpr (std::is_same_v<T, double>)
            db_->Check(sqlite3_bind_double(s, index, value), step);
          else
            db_->Check(sqlite3_bind_int(s, index, static_cast<int>(value)), step);
        },
        field.member);
    ++index;
  }
  if (sqlite3_step(s) != SQLITE_ROW) db_->Fail(step);
  const std::int64_t id = sqlite3_column_int64(s, 0);
  insert.reset();  // finish the statement before COMMIT
  transaction.Commit(step);
  return id;
}

std::vector<StoredSession> SqliteSessionStore::List(const std::string& trainee_id) {
  if (db_->schema_version == 0) return {};  // a read-only empty file: no tables yet
  const std::string step = "list sessions of trainee '" + trainee_id + "'";
  auto statement = db_->Prepare(
      "SELECT " + SessionSelectColumns(db_->schema_version) + " FROM sessions WHERE trainee_id = ? ORDER BY started_unix_s, id", step);
  db_->Check(sqlite3_bind_text(statement.get(), 1, trainee_id.c_str(), -1, SQLITE_TRANSIENT), step);
  std::vector<StoredSession> sessions;
  for (int rc = sqlite3_step(statement.get()); rc != SQLITE_DONE; rc = sqlite3_step(statement.get())) {
    db_->Check(rc, step);
    sessions.push_back(ReadSessionRow(statement.get()));
  }
  return sessions;
}

std::optional<StoredSession> SqliteSessionStore::Get(std::int64_t id) {
  if (db_->schema_version == 0) return std::nullopt;
  const std::string step = "get session " + std::to_string(id);
  auto statement = db_->Prepare("SELECT " + SessionSelectColumns(db_->schema_version) + " FROM sessions WHERE id = ?", step);
  db_->Check(sqlite3_bind_int64(statement.get(), 1, id), step);
  const int rc = sqlite3_step(statement.get());
  db_->Check(rc, step);
  if (rc != SQLITE_ROW) return std::nullopt;
  return ReadSessionRow(statement.get());
}

std::vector<std::string> SqliteSessionStore::ListTrainees() {
  if (db_->schema_version == 0) return {};
  const std::string step = "list trainees";
  auto statement = db_->Prepare(
      "SELECT trainee_id FROM trainees WHERE EXISTS (SELECT 1 FROM sessions s WHERE s.trainee_id = "
      "trainees.trainee_id) "
      "ORDER BY trainee_id",
      step);
  std::vector<std::string> trainees;
  for (int rc = sqlite3_step(statement.get()); rc != SQLITE_DONE; rc = sqlite3_step(statement.get())) {
    db_->Check(rc, step);
    trainees.push_back(ColumnText(statement.get(), 0));
  }
  return trainees;
}

std::string SqliteSessionStore::CheckIntegrity() {
  const std::string integrity = db_->QueryAllText("PRAGMA integrity_check", "integrity check");
  if (integrity != "ok") return integrity;
  const std::string orphans = db_->QueryAllText("PRAGMA foreign_key_check", "foreign key check");
  if (!orphans.empty()) return "foreign_key_check: sessions without trainee in table " + orphans;
  return "ok";
}

int SqliteSessionStore::SchemaVersion() {
  return std::stoi(db_->QueryText("PRAGMA user_version", "read schema version"));
}

std::string SqliteSessionStore::Describe() const { return db_->location; }

std::string SqliteSessionStore::JournalMode() { return db_->QueryText("PRAGMA journal_mode", "read journal mode"); }

}  // namespace vesica::app
