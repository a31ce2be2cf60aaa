#include "app/records/sql_schema.h"

#include <type_traits>
#include <variant>

#include "app/records/metric_fields.h"

namespace vesica::app {
namespace {

// Metric names are quoted: PostgreSQL would otherwise fold "max_force_N" to lower case.
std::string Quoted(const char* name) { return std::string("\"") + name + "\""; }

std::string MetricColumnType(const MetricField& field, SqlDialect dialect) {
  const bool pg = dialect == SqlDialect::kPostgres;
  return std::visit(
      [&](auto member) -> std::string {
        using T = std::remove_cvref_t<decltype(SessionMetrics{}.*member)>;
        if constexpr (std::is_same_v<T, double>)
          return pg ? "DOUBLE PRECISION" : "REAL";
        else if constexpr (std::is_same_v<T, int>)
          return "INTEGER";
        else
          return pg ? "BOOLEAN" : "INTEGER CHECK (" + Quoted(field.name) + " IN (0, 1))";
      },
      field.member);
}

std::string Placeholder(SqlDialect dialect, int index_from_1) {
  if (dialect == SqlDialect::kSqlite) return "?";
  std::string placeholder = "$";  // appended, not "$" + ...: GCC 12 warns falsely (-Wrestrict)
  placeholder += std::to_string(index_from_1);
  return placeholder;
}

// ALTER TABLE statements adding the metric columns that schema `version` introduced, default 0.
void AddMetricColumnsOf(int version, SqlDialect dialect, std::vector<std::string>& statements) {
  const bool pg = dialect == SqlDialect::kPostgres;
  for (const auto& field : kMetricFields) {
    if (field.since_schema != version) continue;
    const bool flag = std::holds_alternative<bool SessionMetrics::*>(field.member);
    const std::string zero = flag && pg ? "FALSE" : "0";
    statements.push_back("ALTER TABLE sessions ADD COLUMN " + Quoted(field.name) + " " +
                         MetricColumnType(field, dialect) + " NOT NULL DEFAULT " + zero);
  }
}

}  // namespace

std::vector<std::string> CreateSchemaV1Sql(SqlDialect dialect) {
  const bool pg = dialect == SqlDialect::kPostgres;
  std::string sessions =
      "CREATE TABLE sessions (\n"
      "  id " +
      std::string(pg ? "BIGINT GENERATED ALWAYS AS IDENTITY PRIMARY KEY" : "INTEGER PRIMARY KEY") +
      ",\n"
      "  trainee_id TEXT NOT NULL REFERENCES trainees(trainee_id),\n"
      "  scenario TEXT NOT NULL,\n"
      "  station TEXT NOT NULL,\n"
      "  started_unix_s BIGINT NOT NULL,\n"
      "  ended_unix_s BIGINT NOT NULL,\n"
      "  input_recording_path TEXT NOT NULL";
  for (const auto& field : kMetricFields) {
    if (field.since_schema != 1) continue;
    sessions += ",\n  " + Quoted(field.name) + " " + MetricColumnType(field, dialect) + " NOT NULL";
  }
  sessions += "\n)";
  return {
      "CREATE TABLE trainees (trainee_id TEXT PRIMARY KEY)",
      sessions,
      "CREATE INDEX sessions_by_trainee ON sessions(trainee_id, started_unix_s, id)",
  };
}

std::vector<std::string> MigrateSchemaV1ToV2Sql(SqlDialect dialect) {
  const bool pg = dialect == SqlDialect::kPostgres;
  const std::string flag = pg ? "BOOLEAN NOT NULL DEFAULT FALSE" : "INTEGER NOT NULL DEFAULT 0";
  return {
      "ALTER TABLE sessions ADD COLUMN replay " + flag + (pg ? "" : " CHECK (replay IN (0, 1))"),
      "ALTER TABLE sessions ADD COLUMN unfinished " + flag + (pg ? "" : " CHECK (unfinished IN (0, 1))"),
      std::string("ALTER TABLE sessions ADD COLUMN physics_lag_s ") + (pg ? "DOUBLE PRECISION" : "REAL") +
          " NOT NULL DEFAULT 0",
  };
}

std::vector<std::string> MigrateSchemaV2ToV3Sql(SqlDialect dialect) {
  std::vector<std::string> statements{
      "ALTER TABLE sessions ADD COLUMN procedure TEXT NOT NULL DEFAULT 'cholecystectomy' CHECK (procedure IN "
      "('cholecystectomy', 'needle_biopsy'))"};
  AddMetricColumnsOf(3, dialect, statements);
  return statements;
}

std::vector<std::string> MigrateSchemaV3ToV4Sql(SqlDialect dialect) {
  std::vector<std::string> statements;
  AddMetricColumnsOf(4, dialect, statements);
  return statements;
}

std::string InsertSessionSql(SqlDialect dialect) {
  std::string columns =
      "trainee_id, scenario, station, started_unix_s, ended_unix_s, input_recording_path, replay, unfinished, "
      "physics_lag_s, procedure";
  for (const auto& field : kMetricFields) columns += ", " + Quoted(field.name);
  std::string values;
  const int count = kSessionHeadColumns - 1 + static_cast<int>(kMetricFields.size());
  for (int i = 1; i <= count; ++i) values += (i > 1 ? ", " : "") + Placeholder(dialect, i);
  return "INSERT INTO sessions (" + columns + ") VALUES (" + values + ") RETURNING id";
}

std::string InsertTraineeSql(SqlDialect dialect) {
  return "INSERT INTO trainees (trainee_id) VALUES (" + Placeholder(dialect, 1) + ") ON CONFLICT DO NOTHING";
}

std::string SessionSelectColumns(int schema_version) {
  std::string columns = "id, trainee_id, scenario, station, started_unix_s, ended_unix_s, input_recording_path, ";
  columns += schema_version >= 2 ? "replay, unfinished, physics_lag_s" : "0, 0, 0";
  columns += schema_version >= 3 ? ", procedure" : ", 'cholecystectomy'";
  for (const auto& field : kMetricFields)
    columns += ", " + (field.since_schema <= schema_version ? Quoted(field.name) : "0");
  return columns;
}

}  // namespace vesica::app
