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
// Version 3 adds to sessions: procedure (text, 'cholecystectomy' or 'needle_biopsy', default
//   'cholecystectomy') and the needle-biopsy metrics (kMetricFields with since_schema 3), default 0.
// Version 4 adds to sessions: the Calot's triangle metrics of a cholecystectomy (kMetricFields
//   with since_schema 4, calot_step first), default 0: a session stored before reads as one
//   without the Calot step.

#include <string>
#include <vector>

namespace vesica::app {

enum class SqlDialect { kSqlite, kPostgres };

/// Statements that create schema version 1 in an empty database (run in one transaction): the
/// metric columns of kMetricFields with since_schema 1.
std::vector<std::string> CreateSchemaV1Sql(SqlDialect dialect);

/// Statements that turn schema version 1 into version 2 (run in one transaction).
std::vector<std::string> MigrateSchemaV1ToV2Sql(SqlDialect dialect);

/// Statements that turn schema version 2 into version 3 (run in one transaction).
std::vector<std::string> MigrateSchemaV2ToV3Sql(SqlDialect dialect);

/// Statements that turn schema version 3 into version 4 (run in one transaction).
std::vector<std::string> MigrateSchemaV3ToV4Sql(SqlDialect dialect);

/// INSERT INTO sessions (...) VALUES (...) with the parameters in SessionParameterOrder, and
/// RETURNING id.
std::string InsertSessionSql(SqlDialect dialect);

/// INSERT INTO trainees ... ON CONFLICT DO NOTHING, one parameter: the trainee id.
std::string InsertTraineeSql(SqlDialect dialect);

/// "id, trainee_id, scenario, station, started_unix_s, ended_unix_s, input_recording_path,
/// replay, unfinished, physics_lag_s, procedure, <metrics in kMetricFields order>" for SELECTs;
/// ReadSessionRow in each backend follows it.
/// For a read-only store of an older `schema_version`, the missing columns read as their
/// defaults (replay 0, unfinished 0, physics_lag_s 0, procedure 'cholecystectomy', metrics 0).
std::string SessionSelectColumns(int schema_version);

/// Number of leading non-metric columns in SessionSelectColumns (id ... procedure).
inline constexpr int kSessionHeadColumns = 11;

}  // namespace vesica::app
