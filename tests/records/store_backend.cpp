#include "tests/records/store_backend.h"

#include <libpq-fe.h>
#include <sqlite3.h>

#include <stdexcept>
#include <string>
#include <vector>

#include "tests/records/postgres_test_server.h"

namespace vesica::app::testing {
namespace {

// The same statements in both dialects; the ghost rows make the transaction large enough that
// SQLite has to spill it to the WAL before COMMIT (cache_size is set tiny below).
std::vector<std::string> UncommittedWriteSql() {
  const std::string filler(200, 'x');
  return {
      "UPDATE sessions SET slips = slips + 1000",
      "DELETE FROM sessions WHERE id % 2 = 0",
      "INSERT INTO trainees (trainee_id) VALUES ('ghost')",
      "INSERT INTO trainees (trainee_id) WITH RECURSIVE n(i) AS (SELECT 1 UNION ALL SELECT i + 1 FROM n WHERE i < "
      "3000) SELECT 'ghost-' || i || '-" +
          filler + "' FROM n",
  };
}

void SqliteUncommittedWrite(const std::string& path) {
  sqlite3* db = nullptr;  // left open on purpose: the process is killed holding the transaction
  if (sqlite3_open(path.c_str(), &db) != SQLITE_OK) throw std::runtime_error("sqlite3_open " + path);
  const auto exec = [&](const std::string& sql) {
    if (sqlite3_exec(db, sql.c_str(), nullptr, nullptr, nullptr) != SQLITE_OK) {
      throw std::runtime_error(sql + ": " + sqlite3_errmsg(db));
    }
  };
  exec("PRAGMA cache_size = 10");
  exec("BEGIN IMMEDIATE");
  for (const auto& sql : UncommittedWriteSql()) exec(sql);
}

void PostgresUncommittedWrite(const std::string& conninfo) {
  PGconn* conn = PQconnectdb(conninfo.c_str());  // left open on purpose, as above
  if (PQstatus(conn) != CONNECTION_OK) throw std::runtime_error(std::string("connect: ") + PQerrorMessage(conn));
  const auto exec = [&](const std::string& sql) {
    PGresult* result = PQexec(conn, sql.c_str());
    const bool ok = PQresultStatus(result) == PGRES_COMMAND_OK || PQresultStatus(result) == PGRES_TUPLES_OK;
    PQclear(result);
    if (!ok) throw std::runtime_error(sql + ": " + PQerrorMessage(conn));
  };
  exec("BEGIN");
  for (const auto& sql : UncommittedWriteSql()) exec(sql);
}

}  // namespace

std::string StoreBackend::Unavailable() const {
  if (name_ != "postgres") return "";
  const auto& server = PostgresTestServer::Shared();
  return server.running() ? "" : "the test PostgreSQL server did not start: " + server.error();
}

std::string StoreBackend::NewLocation() {
  if (name_ == "postgres") return PostgresTestServer::Shared().NewDatabase();
  return (dir_.path() / ("sessions-" + std::to_string(++next_file_) + ".sqlite")).string();
}

void StoreBackend::SetSchemaVersion(const std::string& location, int version) const {
  if (name_ == "postgres") {
    PostgresTestServer::Query(location, "UPDATE vesica_schema SET version = " + std::to_string(version));
    return;
  }
  sqlite3* db = nullptr;
  const int rc = sqlite3_open(location.c_str(), &db);
  const std::string sql = "PRAGMA user_version = " + std::to_string(version);
  const bool ok = rc == SQLITE_OK && sqlite3_exec(db, sql.c_str(), nullptr, nullptr, nullptr) == SQLITE_OK;
  const std::string reason = db != nullptr ? sqlite3_errmsg(db) : "out of memory";
  sqlite3_close(db);
  if (!ok) throw std::runtime_error(location + ": " + sql + ": " + reason);
}

void StoreBackend::StartUncommittedWrite(const std::string& location) const {
  if (name_ == "postgres") {
    PostgresUncommittedWrite(location);
  } else {
    SqliteUncommittedWrite(location);
  }
}

}  // namespace vesica::app::testing
