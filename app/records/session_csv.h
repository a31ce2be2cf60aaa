#pragma once
// CSV export of sessions (RFC 4180: comma separated, CRLF-free "\n" rows, fields with a comma,
// quote or line break quoted with doubled quotes). Columns, in order:
//   id, trainee_id, scenario, station, started_utc, ended_utc, input_recording_path, replay,
//   unfinished, physics_lag_s, procedure, then every SessionMetrics field in its display unit, the unit in
//   the column's name (metric_units.h: duration_s, path_length_left_cm, liver_damage_mm2, ...).
// Times are ISO-8601 UTC ("2026-11-23T03:20:00Z"); doubles (the display value) in shortest
// round-trip form; bools as 1/0.

#include <iosfwd>
#include <string>
#include <vector>

#include "app/records/session_record.h"

namespace vesica::app {

/// The header row's column names.
std::vector<std::string> SessionCsvColumns();

/// Writes the header row and one row per session.
void WriteSessionsCsv(const std::vector<StoredSession>& sessions, std::ostream& out);

}  // namespace vesica::app
