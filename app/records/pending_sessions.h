#pragma once
// Sessions that could not be stored wait in a pending file and are stored at the next start:
// a database that is locked, corrupt, on a full disk or on a server that is down never costs a
// finished session. The file is CSV (RFC 4180), a header row then one session a row:
//   trainee_id, scenario, station, started_unix_s, ended_unix_s, input_recording_path, replay,
//   unfinished, physics_lag_s, procedure, then every SessionMetrics field (kMetricFields order);
// doubles in shortest round-trip form (bit-exact), bools 1/0. Rows are read by the header's
// column names, so a file an older build left (without procedure, the biopsy or the Calot metrics)
// reads with those at their defaults.

#include <filesystem>
#include <string>
#include <vector>

#include "app/records/session_record.h"
#include "app/records/session_store.h"

namespace vesica::app {

/// Where the sessions of `location` wait: "<file>.pending.csv" next to an SQLite file; for a
/// PostgreSQL location "pending-sessions.csv" in the default data folder (default_location.h).
std::filesystem::path PendingSessionsPath(const std::string& location);

/// Appends `record` (creating the file, its folder and header), flushed to disk before it
/// returns. Throws RecordsError naming the file and the system's reason.
void KeepPendingSession(const std::filesystem::path& path, const SessionRecord& record);

/// Rewrites a pending file that an older build left in this build's columns (a file that does not
/// read is renamed to "<path>.unreadable" instead). KeepPendingSession calls it before appending.
void RewriteInThisBuildsColumns(const std::filesystem::path& path);

/// The sessions waiting in `path`, oldest first; none when there is no file. Throws RecordsError
/// naming the file and line of a row that does not read.
std::vector<SessionRecord> ReadPendingSessions(const std::filesystem::path& path);

struct PendingStoreResult {
  int stored = 0;     ///< added to the store and gone from the file
  int left = 0;       ///< still waiting (the store refused them)
  std::string error;  ///< why the first one left could not be stored; empty when none is left
};

/// Adds every waiting session to `store`; the file keeps exactly those that failed (it is
/// removed when none is left). Throws RecordsError when the file cannot be read or rewritten.
PendingStoreResult StorePendingSessions(const std::filesystem::path& path, SessionStore& store);

}  // namespace vesica::app
