#include "app/records/postgres_session_store.h"

#include <libpq-fe.h>

#include <charconv>
#include <regex>
#include <variant>

#include "app/records/metric_fields.h"
#include "app/records/sql_schema.h"

namespace vesica::app {
namespace {

struct ResultDeleter {
  void operator()(PGresult* result) const { PQclear(result); }
};
using Result = std::unique_ptr<PGresult, ResultDeleter>;

struct ConnDeleter {
  void operator()(PGconn* conn) const { PQfinish(conn); }
};

// libpq's messages span lines ("...failed: ...\n\tIs the server running..."): one line for logs.
std::string OneLine(const std::string& text) {
  std::string line;
  for (char c : text) {
    if (c == '\n' || c == '\t') {
      if (!line.empty() && line.back() != ' ') line += ' ';
    } else {
      line += c;
    }
  }
  while (!line.empty() && line.back() == ' ') line.pop_back();
  return line;
}

// Any one server/session lock id; held only while migrating.
constexpr const char* kMigrationLockSql = "SELECT pg_advisory_xact_lock(7206130001)";

}  // namespace

namespace detail {

// The connection and the error path every call shares: "session database LOCATION: STEP: libpq says".
struct PgConnection {
  std::string location;  // masked
  std::unique_ptr<PGconn, ConnDeleter> conn;

  [[noreturn]] void Fail(const std::string& step, const std::string& reason) const {
    throw RecordsError("session database " + location + ": " + step + ": " + OneLine(reason));
  }

  // A connection the server dropped (restart, admin, network) is re-established once per call.
  void EnsureConnected(const std::string& step) {
    if (PQstatus(conn.get()) == CONNECTION_OK) return;
    PQreset(conn.get());
    if (PQstatus(conn.get()) != CONNECTION_OK) Fail(step + ": reconnect", PQerrorMessage(conn.get()));
  }

  Result Exec(const std::string& sql, const std::vector<std::string>& params, const std::string& step) const {
    std::vector<const char*> values;
    values.reserve(params.size());
    for (const auto& p : params) values.push_back(p.c_str());
    Result result(PQexecParams(conn.get(), sql.c_str(), static_cast<int>(values.size()), nullptr, values.data(),
                               nullptr, nullptr, 0));
    const ExecStatusType status = result ? PQresultStatus(result.get()) : PGRES_FATAL_ERROR;
    if (status != PGRES_COMMAND_OK && status != PGRES_TUPLES_OK) {
      std::string reason = result ? PQresultErrorMessage(result.get()) : "";
      if (reason.empty()) reason = PQerrorMessage(conn.get());
      if (PQstatus(conn.get()) != CONNECTION_OK) reason = "connection lost: " + reason;
      Fail(step, reason);
    }
    return result;
  }
};

}  // namespace detail

namespace {

// Rolls back unless committed (skipped when the connection is gone: the server rolls back).
class Transaction {
 public:
  Transaction(const detail::PgConnection& pg, const std::string& step) : pg_(pg) {
    pg_.Exec("BEGIN", {}, step + ": begin");
  }
  ~Transaction() {
    if (!committed_ && PQstatus(pg_.conn.get()) == CONNECTION_OK) PQclear(PQexec(pg_.conn.get(), "ROLLBACK"));
  }
  void Commit(const std::string& step) {
    pg_.Exec("COMMIT", {}, step + ": commit");
    committed_ = true;
  }

 private:
  const detail::PgConnection& pg_;
  bool committed_ = false;
};

template <typename T>
T ParseNumber(const char* text, const detail::PgConnection& pg, const std::string& step) {
  T value{};
  const char* end = text + std::char_traits<char>::length(text);
  const auto [ptr, error] = std::from_chars(text, end, value);
  if (error != std::errc() || ptr != end) pg.Fail(step, std::string("unexpected number '") + text + "' from server");
  return value;
}

StoredSession ReadSessionRow(const PGresult* result, int row, const detail::PgConnection& pg, const std::string& step) {
  const auto text = [&](int column) { return PQgetvalue(result, row, column); };
  StoredSession session;
  session.id = ParseNumber<std::int64_t>(text(0), pg, step);
  auto& r = session.record;
  r.trainee_id = text(1);
  r.scenario = text(2);
  r.station = text(3);
  r.started_unix_s = ParseNumber<std::int64_t>(text(4), pg, step);
  r.ended_unix_s = ParseNumber<std::int64_t>(text(5), pg, step);
  r.input_recording_path = text(6);
  r.replay = text(7)[0] == 't';
  r.unfinished = text(8)[0] == 't';
  r.physics_lag_s = ParseNumber<double>(text(9), pg, step);
  const auto procedure = ParseProcedure(text(10));
  if (!procedure) pg.Fail(step, std::string("unknown procedure '") + text(10) + "' in session " + text(0));
  r.procedure = *procedure;
  int column = kSessionHeadColumns;
  for (const auto& field : kMetricFields) {
    std::visit(
        [&](auto member) {
          using T = std::remove_cvref_t<decltype(r.metrics.*member)>;
          if constexpr (std::is_same_v<T, bool>)
            r.metrics.*member = text(column)[0] == 't';
          else
            r.metrics.*member = ParseNumber<T>(text(column), pg, step);
        },
        field.member);
    ++column;
  }
  return session;
}

// Shortest text that parses back to the same double (the server keeps all 17 digits).
std::string DoubleText(double value) {
  char text[32];
  const auto result = std::to_chars(text, text + sizeof text, value);
  return std::string(text, result.ptr);
}

std::vector<std::string> SessionParams(const SessionRecord& r) {
  std::vector<std::string> params{
      r.trainee_id,          r.scenario, r.station, std::to_string(r.started_unix_s), std::to_string(r.ended_unix_s),
      r.input_recording_path, r.replay ? "true" : "false", r.unfinished ? "true" : "false", DoubleText(r.physics_lag_s),
      ProcedureKey(r.procedure)};
  for (const auto& field : kMetricFields) {
    std::visit(
        [&](auto member) {
          using T = std::remove_cvref_t<decltype(r.metrics.*member)>;
          if constexpr (std::is_same_v<T, double>)
            params.push_back(DoubleText(r.metrics.*member));
          else if constexpr (std::is_same_v<T, bool>)
            params.push_back(r.metrics.*member ? "true" : "false");
          else
            params.push_back(std::to_string(r.metrics.*member));
        },
        field.member);
  }
  return params;
}

}  // namespace

std::string MaskPassword(const std::string& connection_string) {
  static const std::regex uri_password(R"(^(postgres(?:ql)?://[^:@/?]*:)[^@/?]*@)");
  static const std::regex query_password(R"(([?&]password=)[^&]*)");
  static const std::regex keyword_password(R"((password\s*=\s*)('(?:[^'\\]|\\.)*'|\S+))");
  // A URI's query is not keyword=value text: "password=" there ends at '&', not at a space.
  if (connection_string.starts_with("postgresql://") || connection_string.starts_with("postgres://")) {
    const std::string masked = std::regex_replace(connection_string, uri_password, "$1***@");
    return std::regex_replace(masked, query_password, "$1***");
  }
  return std::regex_replace(connection_string, keyword_password, "$1***");
}

PostgresSessionStore::PostgresSessionStore(const std::string& connection_string)
    : pg_(std::make_unique<detail::PgConnection>()) {
  pg_->location = MaskPassword(connection_string);

  char* parse_error = nullptr;
  PQconninfoOption* options = PQconninfoParse(connection_string.c_str(), &parse_error);
  if (options == nullptr) {
    const std::string reason = parse_error != nullptr ? parse_error : "out of memory";
    PQfreemem(parse_error);
    pg_->Fail("bad connection string", reason);
  }
  PQconninfoFree(options);

  // connect_timeout first so that one given in the string overrides it (expand_dbname = 1).
  const char* keywords[] = {"connect_timeout", "dbname", nullptr};
  const char* values[] = {"10", connection_string.c_str(), nullptr};
  pg_->conn.reset(PQconnectdbParams(keywords, values, 1));
  if (pg_->conn == nullptr) pg_->Fail("connect", "out of memory");
  if (PQstatus(pg_->conn.get()) != CONNECTION_OK) pg_->Fail("connect", PQerrorMessage(pg_->conn.get()));
  PQsetNoticeProcessor(
      pg_->conn.get(), [](void*, const char*) {}, nullptr);  // no NOTICE chatter on stderr

  int version = SchemaVersion();
  if (version > kSessionSchemaVersion) {
    pg_->Fail("open", "schema version " + std::to_string(version) +
                          " was written by a newer Vesica (this build knows up to " +
                          std::to_string(kSessionSchemaVersion) + ")");
  }
  if (version < kSessionSchemaVersion) {
    const std::string step =
        "migrate schema " + std::to_string(version) + " -> " + std::to_string(kSessionSchemaVersion);
    Transaction transaction(*pg_, step);
    pg_->Exec(kMigrationLockSql, {}, step + ": lock");
    pg_->Exec("CREATE TABLE IF NOT EXISTS vesica_schema (version INTEGER NOT NULL)", {}, step);
    version = SchemaVersion();  // re-read under the lock: another station may have migrated
    if (version == 0) {
      for (const auto& sql : CreateSchemaV1Sql(SqlDialect::kPostgres)) pg_->Exec(sql, {}, step);
      version = 1;
    }
    if (version == 1) {
      for (const auto& sql : MigrateSchemaV1ToV2Sql(SqlDialect::kPostgres)) pg_->Exec(sql, {}, step);
      version = 2;
    }
    if (version == 2) {
      for (const auto& sql : MigrateSchemaV2ToV3Sql(SqlDialect::kPostgres)) pg_->Exec(sql, {}, step);
      version = 3;
    }
    if (version == 3) {
      for (const auto& sql : MigrateSchemaV3ToV4Sql(SqlDialect::kPostgres)) pg_->Exec(sql, {}, step);
    }
    pg_->Exec("DELETE FROM vesica_schema", {}, step);
    pg_->Exec("INSERT INTO vesica_schema (version) VALUES ($1)", {std::to_string(kSessionSchemaVersion)}, step);
    transaction.Commit(step);
  }
}

PostgresSessionStore::~PostgresSessionStore() = default;

std::int64_t PostgresSessionStore::Add(const SessionRecord& record) {
  ValidateForAdd(record);
  const std::string step = "add session of trainee '" + record.trainee_id + "'";
  pg_->EnsureConnected(step);
  Transaction transaction(*pg_, step);
  pg_->Exec(InsertTraineeSql(SqlDialect::kPostgres), {record.trainee_id}, step);
  const Result inserted = pg_->Exec(InsertSessionSql(SqlDialect::kPostgres), SessionParams(record), step);
  const auto id = ParseNumber<std::int64_t>(PQgetvalue(inserted.get(), 0, 0), *pg_, step);
  transaction.Commit(step);
  return id;
}

std::vector<StoredSession> PostgresSessionStore::List(const std::string& trainee_id) {
  const std::string step = "list sessions of trainee '" + trainee_id + "'";
  pg_->EnsureConnected(step);
  const Result result =
      pg_->Exec("SELECT " + SessionSelectColumns(kSessionSchemaVersion) + " FROM sessions WHERE trainee_id = $1 ORDER BY started_unix_s, id",
                {trainee_id}, step);
  std::vector<StoredSession> sessions;
  for (int row = 0; row < PQntuples(result.get()); ++row) {
    sessions.push_back(ReadSessionRow(result.get(), row, *pg_, step));
  }
  return sessions;
}

std::optional<StoredSession> PostgresSessionStore::Get(std::int64_t id) {
  const std::string step = "get session " + std::to_string(id);
  pg_->EnsureConnected(step);
  const Result result =
      pg_->Exec("SELECT " + SessionSelectColumns(kSessionSchemaVersion) + " FROM sessions WHERE id = $1", {std::to_string(id)}, step);
  if (PQntuples(result.get()) == 0) return std::nullopt;
  return ReadSessionRow(result.get(), 0, *pg_, step);
}

std::vector<std::string> PostgresSessionStore::ListTrainees() {
  const std::string step = "list trainees";
  pg_->EnsureConnected(step);
  const Result result = pg_->Exec(
      "SELECT trainee_id FROM trainees t WHERE EXISTS (SELECT 1 FROM sessions s WHERE s.trainee_id = t.trainee_id) "
      "ORDER BY trainee_id COLLATE \"C\"",
      {}, step);
  std::vector<std::string> trainees;
  for (int row = 0; row < PQntuples(result.get()); ++row) trainees.emplace_back(PQgetvalue(result.get(), row, 0));
  return trainees;
}

std::string PostgresSessionStore::CheckIntegrity() {
  const std::string step = "integrity check";
  pg_->EnsureConnected(step);
  // The server keeps its own files consistent (WAL); what can go wrong is ours: the schema
  // and rows that do not belong together.
  const int version = SchemaVersion();
  if (version != kSessionSchemaVersion) return "schema version " + std::to_string(version);
  const Result orphans = pg_->Exec(
      "SELECT count(*) FROM sessions s WHERE NOT EXISTS (SELECT 1 FROM trainees t WHERE t.trainee_id = s.trainee_id)",
      {}, step);
  const std::string count = PQgetvalue(orphans.get(), 0, 0);
  if (count != "0") return count + " sessions without a trainee row";
  return "ok";
}

int PostgresSessionStore::SchemaVersion() {
  const std::string step = "read schema version";
  pg_->EnsureConnected(step);
  const Result exists = pg_->Exec("SELECT to_regclass('vesica_schema') IS NOT NULL", {}, step);
  if (PQgetvalue(exists.get(), 0, 0)[0] != 't') return 0;
  const Result result = pg_->Exec("SELECT max(version) FROM vesica_schema", {}, step);
  if (PQgetisnull(result.get(), 0, 0)) return 0;
  return ParseNumber<int>(PQgetvalue(result.get(), 0, 0), *pg_, step);
}

std::string PostgresSessionStore::Describe() const { return pg_->location; }

}  // namespace vesica::app
