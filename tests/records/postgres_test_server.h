#pragma once
// A private PostgreSQL server for tests, from Debian's postgresql-15 binaries: initdb into a
// fresh /tmp folder, postgres listening only on a Unix socket in that folder (no TCP port, so
// parallel test processes never collide), stopped (-m immediate) and removed on destruction.
// PostgreSQL refuses to run as root: as root the binaries run as the `postgres` system user
// (runuser) and the folder is chowned to it.
//
// initdb takes seconds, so the first server of a machine leaves a copy of its fresh cluster in
// /tmp/vesica-pg-template-<uid>-<major> and later ones start from a copy of that.
//
// Starting never throws: a server that cannot start keeps the reason in error(), and the tests
// fail with it (they are never skipped).

#include <sys/types.h>

#include <memory>
#include <string>
#include <vector>

#include "tests/records/temp_dir.h"

namespace vesica::app::testing {

class PostgresTestServer {
 public:
  PostgresTestServer();  // initdb + pg_ctl start -w (about a second)
  ~PostgresTestServer();
  PostgresTestServer(const PostgresTestServer&) = delete;
  PostgresTestServer& operator=(const PostgresTestServer&) = delete;

  /// One server per test process, started on first use, stopped at exit.
  static PostgresTestServer& Shared();

  bool running() const { return running_; }
  /// Why the server is not running (with the tail of the initdb / server log).
  const std::string& error() const { return error_; }

  /// libpq keyword/value string for database `dbname` on this server.
  std::string ConnectionString(const std::string& dbname) const;

  /// Creates an empty database with a new name and returns its connection string. Throws
  /// std::runtime_error when the server refuses.
  std::string NewDatabase();

  /// Runs one SQL command as the superuser in database `dbname`; returns the first value of
  /// the first row ("" when none). Throws std::runtime_error on failure.
  std::string AdminQuery(const std::string& dbname, const std::string& sql) const;

  /// Runs one SQL command through any libpq connection string; returns the first value of the
  /// first row ("" when none). Throws std::runtime_error on failure.
  static std::string Query(const std::string& connection_string, const std::string& sql);

  /// pg_ctl stop -m immediate: the server is gone, as after a crash or a pulled cable.
  void Stop();

 private:
  // The uid the server runs as: `postgres` when we are root, else ourselves.
  static uid_t ServerUid();
  // /tmp/vesica-pg-template-<uid>-<major>: a freshly initdb'd cluster kept for later processes.
  std::string TemplatePath() const;
  static bool UsableTemplate(const std::string& path);
  bool RunAsPostgres(const std::vector<std::string>& argv, const std::string& log_path, std::string& why);

  std::unique_ptr<TempDir> dir_;
  std::string bin_dir_;
  bool running_ = false;
  std::string error_;
  int next_database_ = 0;
};

}  // namespace vesica::app::testing
