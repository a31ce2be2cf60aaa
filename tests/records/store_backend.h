#pragma once
// The backends the shared store tests run against: "sqlite" (a file in a temp folder) and
// "postgres" (a fresh database on the test process's private server), and the few things the
// tests do behind the store's back, in each backend's own SQL.

#include <memory>
#include <string>
#include <utility>

#include "tests/records/temp_dir.h"

namespace vesica::app::testing {

class StoreBackend {
 public:
  explicit StoreBackend(std::string name) : name_(std::move(name)) {}

  const std::string& name() const { return name_; }

  /// Empty when the backend is usable, else why not (the test fails with it).
  std::string Unavailable() const;

  /// A location for OpenSessionStore where no store exists yet.
  std::string NewLocation();

  /// Overwrites the stored schema version, as a newer Vesica would have left it.
  void SetSchemaVersion(const std::string& location, int version) const;

  /// Opens a second connection to `location`, begins a write transaction that changes every
  /// session (slips += 1000, even ids deleted), adds trainee "ghost" and a few thousand rows,
  /// and returns with it uncommitted and the connection deliberately left open. For a child
  /// process that is about to be killed. SQLite spills the uncommitted pages into the WAL file.
  void StartUncommittedWrite(const std::string& location) const;

 private:
  std::string name_;
  TempDir dir_;
  int next_file_ = 0;
};

}  // namespace vesica::app::testing
