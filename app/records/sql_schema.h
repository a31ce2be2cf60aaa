#pragma once
// The session schema and statements, generated from kMetricFields for both SQL dialects so
// the two backends store exactly the same columns.
//
// Version 1:
//   trainees(trainee_id TEXT PRIMARY KEY)
//   sessions(id, trainee_id -> trainees, scenario, station, started_unix_s, ended_unix_s,
//            input_recording_path, one column per SessionMetrics field)
//   index sessions_by_trainee(trainee_id, started_unix_s, id)

#include <string>
#include <vector>

namespace vesica::app {

enum class SqlDialect { kSqlite, kPostgres };

/// Statements that create schema version 1 in an empty database (run in one transaction).
std::vector<std::string> CreateSchemaV1Sql(SqlDialect dialect);

/// INSERT INTO sessions (...) VALUES (...) with the parameters in SessionParameterOrder, and
/// RETURNING id.
std::string InsertSessionSql(SqlDialect dialect);

/// INSERT INTO trainees ... ON CONFLICT DO NOTHING, one parameter: the trainee id.
std::string InsertTraineeSql(SqlDialect dialect);

/// "id, trainee_id, scenario, station, started_unix_s, ended_unix_s, input_recording_path,
/// <metrics in kMetricFields order>" for SELECTs; ReadSessionRow in each backend follows it.
std::string SessionSelectColumns();

/// Number of leading non-metric columns in SessionSelectColumns (id ... input_recording_path).
inline constexpr int kSessionHeadColumns = 7;

}  // namespace vesica::app
