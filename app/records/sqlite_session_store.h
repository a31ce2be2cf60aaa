#pragma once
// SessionStore in an SQLite file: WAL journal, synchronous=FULL, one transaction per session,
// schema version in PRAGMA user_version. A process killed at any moment leaves every session
// whose Add returned, and a database that passes integrity_check (WAL recovery on next open).

#include <filesystem>
#include <memory>

#include "app/records/session_store.h"

namespace vesica::app {

namespace detail {
struct SqliteDb;
}  // namespace detail

class SqliteSessionStore final : public SessionStore {
 public:
  /// Opens or creates the file (and its missing folders), migrates the schema, checks the
  /// database (quick_check). Throws RecordsError naming the path and the failing step.
  /// StoreAccess::kReadOnly opens an existing file for reading only: nothing is created,
  /// migrated or switched (journal mode), so a database on a read-only disk or of another user
  /// can be read; an older schema reads with the newer columns' defaults; Add throws.
  explicit SqliteSessionStore(const std::filesystem::path& path, StoreAccess access = StoreAccess::kReadWrite);
  ~SqliteSessionStore() override;

  std::int64_t Add(const SessionRecord& record) override;
  std::vector<StoredSession> List(const std::string& trainee_id) override;
  std::optional<StoredSession> Get(std::int64_t id) override;
  std::vector<std::string> ListTrainees() override;
  std::string CheckIntegrity() override;
  int SchemaVersion() override;
  std::string Describe() const override;

  /// The journal mode SQLite reports ("wal").
  std::string JournalMode();

 private:
  void OpenReadWrite();
  void OpenReadOnly();
  std::unique_ptr<detail::SqliteDb> db_;
};

}  // namespace vesica::app
