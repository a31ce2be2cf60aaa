#pragma once
// The session schema and statements, generated from kMetricFields for both SQL dialects so
// the two backends store exactly the same columns.
//
// Version 1:
//   trainees(trainee_id TEXT PRIMARY KEY)
//   sessions(id, trainee_id -> trainees, scenario, station, started_unix_s, ended_unix_s,
//            input_recording_path, one column per SessionMetrics field)
//   index sessions_by_trainee(trainee_id, started_unix_s, id)
// Version 2 adds to sessions: replay, unfinished (booleans), physics_lag_s (double), default 0.

#include <string>
#include <vector>

namespace vesica::app {

enum class SqlDialect { kSqlite, kPostgres };

/// Statements that create schema version 1 in an empty database (run in one transaction).
std::vector<std::string> CreateSchemaV1Sql(SqlDialect dialect);

/// Statements that turn schema version 1 into version 2 (run in one transaction).
std::vector<std::string> MigrateSchemaV1ToV2Sql(SqlDialect dialect);

/// INSERT INTO sessions (...) VALUES (...) with the parameters in SessionParameterOrder, and
/// RETURNING id.
std::string InsertSessionSql(SqlDialect dialect);

/// INSERT INTO trainees ... ON CONFLICT DO NOTHING, one parameter: the trainee id.
std::string InsertTraineeSql(SqlDialect dialect);

/// "id, trainee_id, scenario, station, started_unix_s, ended_unix_s, input_recording_path,
/// replay, unfinished, physics_lag_s, <metrics in kMetricFields order>" for SELECTs;
/// ReadSessionRow in each backend follows it.
/// For a read-only store of an older `schema_version`, the missing columns read as their
/// defaults (version 1: replay 0, unfinished 0, physics_lag_s 0).
std::string SessionSelectColumns(int schema_version = 2);

/// Number of leading non-metric columns in SessionSelectColumns (id ... physics_lag_s).
inline constexpr int kSessionHeadColumns = 10;

}  // namespace vesica::app
