#pragma once
// Shared by the history tests: a temporary folder, known sessions of two trainees, and a store
// wrapper that fails on demand the way a broken database does (RecordsError).

#include <filesystem>
#include <memory>

#include "app/records/session_store.h"

namespace vesica::app::testing {

class TempDir {
 public:
  TempDir();
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

/// "ana": three sessions (added out of start order), "ben": two. Values are listed in the
/// .cpp; AnaSessions()[i] is ana's session i in start order.
std::vector<SessionRecord> AnaSessions();
std::vector<SessionRecord> BenSessions();

/// An SQLite store at dir/sessions.sqlite holding AnaSessions and BenSessions.
std::unique_ptr<SessionStore> KnownStore(const std::filesystem::path& dir);

/// Passes every call on to `inner` unless the matching flag is set, then throws RecordsError
/// with "session database test.sqlite: <step>: disk I/O error".
class FlakyStore : public SessionStore {
 public:
  explicit FlakyStore(SessionStore& inner) : inner_(inner) {}

  bool fail_list_trainees = false;
  bool fail_list = false;

  std::int64_t Add(const SessionRecord& record) override { return inner_.Add(record); }
  std::vector<StoredSession> List(const std::string& trainee_id) override;
  std::optional<StoredSession> Get(std::int64_t id) override { return inner_.Get(id); }
  std::vector<std::string> ListTrainees() override;
  std::string CheckIntegrity() override { return inner_.CheckIntegrity(); }
  int SchemaVersion() override { return inner_.SchemaVersion(); }
  std::string Describe() const override { return "test.sqlite"; }

 private:
  SessionStore& inner_;
};

}  // namespace vesica::app::testing
