#pragma once
// SessionStore on a PostgreSQL server (libpq), for stations sharing one database. Same schema
// as SQLite (sql_schema.h); the version lives in table vesica_schema. Each session is one
// transaction; a lost connection fails the call with RecordsError and the next call reconnects.

#include <memory>
#include <string>

#include "app/records/session_store.h"

namespace vesica::app {

namespace detail {
struct PgConnection;
}  // namespace detail

class PostgresSessionStore final : public SessionStore {
 public:
  /// `connection_string`: libpq URI ("postgresql://user@host:5432/vesica") or keyword=value
  /// pairs ("host=/run/postgresql dbname=vesica"); connect_timeout defaults to 10 s. Connects,
  /// migrates the schema (under an advisory lock, so stations starting together are safe).
  /// Throws RecordsError naming the masked connection string and what failed.
  explicit PostgresSessionStore(const std::string& connection_string);
  ~PostgresSessionStore() override;

  std::int64_t Add(const SessionRecord& record) override;
  std::vector<StoredSession> List(const std::string& trainee_id) override;
  std::optional<StoredSession> Get(std::int64_t id) override;
  std::vector<std::string> ListTrainees() override;
  std::string CheckIntegrity() override;
  int SchemaVersion() override;
  std::string Describe() const override;

 private:
  std::unique_ptr<detail::PgConnection> pg_;
};

/// The connection string with any password replaced by "***" (URI user:password@, ?password=,
/// keyword password=...), for messages and logs.
std::string MaskPassword(const std::string& connection_string);

}  // namespace vesica::app
