#include "app/records/session_csv.h"

#include <charconv>
#include <ostream>
#include <variant>

#include "app/records/csv_text.h"
#include "app/records/metric_fields.h"
#include "app/records/metric_units.h"

namespace vesica::app {
namespace {



std::string MetricText(const SessionMetrics& metrics, const MetricField& field, double scale) {
  return std::visit(
      [&](auto member) -> std::string {
        const auto value = metrics.*member;
        if constexpr (std::is_same_v<decltype(value), const double>)
          return ShortestDoubleText(value * scale);
        else if constexpr (std::is_same_v<decltype(value), const bool>)
          return value ? "1" : "0";
        else
          return std::to_string(value);
      },
      field.member);
}

}  // namespace

std::vector<std::string> SessionCsvColumns() {
  std::vector<std::string> columns{"id",        "trainee_id",           "scenario", "station",    "started_utc",
                                   "ended_utc", "input_recording_path", "replay",   "unfinished", "physics_lag_s",
                                   "procedure"};
  for (const auto& unit : kMetricDisplayUnits) columns.emplace_back(unit.csv_column);
  return columns;
}

void WriteSessionsCsv(const std::vector<StoredSession>& sessions, std::ostream& out) {
  const auto columns = SessionCsvColumns();
  for (std::size_t i = 0; i < columns.size(); ++i) out << (i > 0 ? "," : "") << columns[i];
  out << '\n';
  for (const auto& session : sessions) {
    const auto& r = session.record;
    out << session.id << ',' << CsvField(r.trainee_id) << ',' << CsvField(r.scenario) << ',' << CsvField(r.station)
        << ',' << FormatUtcIso8601(r.started_unix_s) << ',' << FormatUtcIso8601(r.ended_unix_s) << ','
        << CsvField(r.input_recording_path) << ',' << (r.replay ? 1 : 0) << ',' << (r.unfinished ? 1 : 0) << ','
        << ShortestDoubleText(r.physics_lag_s) << ',' << ProcedureKey(r.procedure);
    for (std::size_t i = 0; i < kMetricFields.size(); ++i)
      out << ',' << MetricText(r.metrics, kMetricFields[i], kMetricDisplayUnits[i].scale);
    out << '\n';
  }
}

}  // namespace vesica::app
