#pragma once
// One finished training session as it is stored: who, what, where, when, and the metrics.

#include <cstdint>
#include <string>

#include "app/records/metric_fields.h"
#include "app/records/procedure.h"
#include "app/records/session_metrics.h"

namespace vesica::app {

struct SessionRecord {
  std::string trainee_id;           // non-empty; the key trainees are listed by
  std::string scenario;             // scenario name (Scenario::name)
  std::int64_t started_unix_s = 0;  // UTC, seconds since 1970-01-01T00:00:00Z
  std::int64_t ended_unix_s = 0;    // UTC, >= started_unix_s
  SessionMetrics metrics;
  std::string input_recording_path;  // recorded instrument input for replay; empty if none
  std::string station;               // which trainer station ran it (host name by default)
  // Schema version 2:
  bool replay = false;       // the input came from a recording (a replay or the demo): not the trainee's own
                             // hands, so it is no step of a learning curve
  bool unfinished = false;   // stored as it stood when the trainer quit (or was told to stop) mid-session
  double physics_lag_s = 0;  // how far the simulation fell behind the wall clock (>= 0): the trainee lived
                             // metrics.duration_s, the tissue only duration_s - physics_lag_s
  // Schema version 3:
  Procedure procedure = Procedure::kCholecystectomy;  // which operation; the metrics of the other are 0

  bool operator==(const SessionRecord&) const = default;
};

/// A record as read back from a store, with the id the store gave it.
struct StoredSession {
  std::int64_t id = 0;
  SessionRecord record;

  bool operator==(const StoredSession&) const = default;
};

/// "2026-11-23T03:20:00Z" for a unix time (UTC, second precision).
std::string FormatUtcIso8601(std::int64_t unix_s);

}  // namespace vesica::app
