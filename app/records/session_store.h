#pragma once
// Where finished sessions are kept: an abstract store with two backends, SQLite (a file on the
// station, the default) and PostgreSQL (shared by several stations). OpenSessionStore picks one
// from a location string. Every failure is a RecordsError whose message names the location
// (passwords masked) and what failed.

#include <cstdint>
#include <iosfwd>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "app/records/session_record.h"

namespace vesica::app {

class RecordsError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class SessionStore {
 public:
  virtual ~SessionStore() = default;

  /// Stores a finished session in one transaction and returns its id. Once Add returns, the
  /// session survives the process being killed. Throws RecordsError for a record that fails
  /// ValidateRecord or when the store cannot write.
  virtual std::int64_t Add(const SessionRecord& record) = 0;

  /// The trainee's sessions, oldest start first (ties by id).
  virtual std::vector<StoredSession> List(const std::string& trainee_id) = 0;

  virtual std::optional<StoredSession> Get(std::int64_t id) = 0;

  /// Every trainee with at least one session, sorted.
  virtual std::vector<std::string> ListTrainees() = 0;

  /// "ok", or a description of what is inconsistent (SQLite: PRAGMA integrity_check and
  /// foreign_key_check; PostgreSQL: schema version and orphaned rows).
  virtual std::string CheckIntegrity() = 0;

  /// The stored schema version (SQLite PRAGMA user_version, PostgreSQL vesica_schema.version).
  virtual int SchemaVersion() = 0;

  /// The location as shown in messages (passwords masked).
  virtual std::string Describe() const = 0;

  /// Header row and one row per session of the trainee, in List order; columns in
  /// session_csv.h.
  void ExportCsv(const std::string& trainee_id, std::ostream& out);

 protected:
  /// ValidateRecord, with the store's location in front of the message (for Add).
  void ValidateForAdd(const SessionRecord& record) const;
};

/// Whether a store is opened to write sessions (the trainer) or only to read them (vesica-records,
/// the history view of another station's file).
enum class StoreAccess { kReadWrite, kReadOnly };

/// The schema version this build writes; older stores are migrated on open, newer ones refused.
inline constexpr int kSessionSchemaVersion = 4;

/// Throws RecordsError naming the first bad field (empty trainee, end before start, negative or
/// non-finite metric or physics_lag_s).
void ValidateRecord(const SessionRecord& record);

/// True for a libpq connection string: a "postgresql://" or "postgres://" URI, or keyword=value
/// pairs ("host=db dbname=vesica"). Anything else is a file path (write "./a=b.sqlite" for a
/// file whose name looks like a keyword=value pair).
bool IsConnectionString(const std::string& location);

/// PostgreSQL for a connection string, otherwise an SQLite file (created with its folders if
/// missing; with kReadOnly an existing file opened read-only). Throws RecordsError when the
/// store cannot be opened or its schema is unusable.
std::unique_ptr<SessionStore> OpenSessionStore(const std::string& location,
                                               StoreAccess access = StoreAccess::kReadWrite);

}  // namespace vesica::app
