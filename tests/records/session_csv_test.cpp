// The CSV export, read back with an independent RFC 4180 reader and compared value by value.

#include "app/records/session_csv.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <sstream>
#include <variant>

#include "app/records/metric_fields.h"
#include "app/records/metric_units.h"
#include "app/records/session_store.h"
#include "tests/records/csv_reader.h"
#include "tests/records/sample_records.h"
#include "tests/records/temp_dir.h"

namespace vesica::app {
namespace {

using ::testing::ElementsAre;
using testing::ReadCsv;
using testing::SampleRecord;
using testing::TempDir;

// Checks one CSV row against the session it came from; doubles (in their display unit) parse
// back bit for bit.
void ExpectRowIs(const std::vector<std::string>& row, const StoredSession& session) {
  const auto& r = session.record;
  ASSERT_EQ(row.size(), 11 + kMetricFields.size());
  EXPECT_EQ(row[0], std::to_string(session.id));
  EXPECT_EQ(row[1], r.trainee_id);
  EXPECT_EQ(row[2], r.scenario);
  EXPECT_EQ(row[3], r.station);
  EXPECT_EQ(row[4], FormatUtcIso8601(r.started_unix_s));
  EXPECT_EQ(row[5], FormatUtcIso8601(r.ended_unix_s));
  EXPECT_EQ(row[6], r.input_recording_path);
  EXPECT_EQ(row[7], r.replay ? "1" : "0");
  EXPECT_EQ(row[8], r.unfinished ? "1" : "0");
  EXPECT_EQ(std::strtod(row[9].c_str(), nullptr), r.physics_lag_s);
  EXPECT_EQ(row[10], ProcedureKey(r.procedure));
  std::size_t column = 11;
  for (const auto& field : kMetricFields) {
    const double scale = FindMetricDisplayUnit(field.name)->scale;
    const std::string& text = row[column++];
    std::visit(
        [&](auto member) {
          using T = std::remove_cvref_t<decltype(r.metrics.*member)>;
          if constexpr (std::is_same_v<T, double>) {
            char* end = nullptr;
            EXPECT_EQ(std::strtod(text.c_str(), &end), r.metrics.*member * scale) << field.name << " = " << text;
            EXPECT_EQ(*end, '\0') << field.name;
          } else if constexpr (std::is_same_v<T, bool>) {
            EXPECT_EQ(text, r.metrics.*member ? "1" : "0") << field.name;
          } else {
            EXPECT_EQ(text, std::to_string(r.metrics.*member)) << field.name;
          }
        },
        field.member);
  }
}

TEST(FormatUtcIso8601Test, KnownInstants) {
  EXPECT_EQ(FormatUtcIso8601(0), "1970-01-01T00:00:00Z");
  EXPECT_EQ(FormatUtcIso8601(951782400), "2000-02-29T00:00:00Z");
  EXPECT_EQ(FormatUtcIso8601(1795406400 + 3723), "2026-11-23T05:02:03Z");
  EXPECT_EQ(FormatUtcIso8601(-1), "1969-12-31T23:59:59Z");
}

TEST(SessionCsvTest, HeaderIsFixedColumnsThenEveryMetricNamedWithItsDisplayUnit) {
  // The units of the trainer's panel and history (s, cm, mm², N, %), not the stored SI metres.
  EXPECT_THAT(SessionCsvColumns(),
              ElementsAre("id", "trainee_id", "scenario", "station", "started_utc", "ended_utc", "input_recording_path",
                          "replay", "unfinished", "physics_lag_s", "procedure", "duration_s", "path_length_left_cm",
                          "path_length_right_cm", "slips", "cautery_on_s", "liver_damage_mm2", "gallbladder_damage_mm2",
                          "max_force_N", "mean_force_N", "tissue_removed_percent", "springs_cut", "springs_total",
                          "gallbladder_free", "perforation", "success", "biopsy_sampled", "time_to_sample_s",
                          "sample_distance_mm", "nogo_crossings", "insertion_attempts", "calot_step", "cvs_achieved",
                          "cvs_time_s", "cvs_before_first_clip", "cystic_duct_clips", "cystic_artery_clips",
                          "cystic_duct_clips_correct", "cystic_artery_clips_correct",
                          "cystic_duct_divided_between_clips", "cystic_artery_divided_between_clips", "bleeding_events",
                          "bile_leaks", "bile_duct_injuries", "calot_passed"));
}

TEST(SessionCsvTest, EmptyListIsHeaderOnly) {
  std::ostringstream out;
  WriteSessionsCsv({}, out);
  const auto rows = ReadCsv(out.str());
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_EQ(rows[0], SessionCsvColumns());
}

TEST(SessionCsvTest, RowsReadBackToTheSameValuesIncludingAwkwardText) {
  std::vector<StoredSession> sessions{{7, SampleRecord(0)}, {12, SampleRecord(1)}, {13, SampleRecord(2)}};
  sessions[1].record.scenario = "fundus-first, \"hard\" variant";
  sessions[1].record.station = "line one\nline two";
  sessions[2].record.input_recording_path = "/recordings/a,b\"c\".rec";
  std::ostringstream out;
  WriteSessionsCsv(sessions, out);
  const auto rows = ReadCsv(out.str());
  ASSERT_EQ(rows.size(), 4u);
  EXPECT_EQ(rows[0], SessionCsvColumns());
  for (std::size_t i = 0; i < sessions.size(); ++i) {
    SCOPED_TRACE("row " + std::to_string(i + 1));
    ExpectRowIs(rows[i + 1], sessions[i]);
  }
  // A literal check of one plain row, so the format cannot drift unnoticed.
  EXPECT_EQ(rows[1][4], "2026-11-23T04:00:00Z");
  EXPECT_EQ(rows[1][10], "cholecystectomy");
  EXPECT_EQ(rows[3][10], "needle_biopsy");
  EXPECT_EQ(rows[1][11], "300.0833333333333");   // duration_s = 299.75 + 1/3
  EXPECT_EQ(rows[1][12], "14.285714285714285");  // path_length_left_cm = 100 / 7
  EXPECT_EQ(rows[1][16], "15");                  // liver_damage_mm2 = 1.5e-5 m² x 1e6
  EXPECT_EQ(rows[1][20], "50");                  // tissue_removed_percent = 1/2 x 100
  EXPECT_EQ(rows[3][28], "10.500001");           // sample_distance_mm = (0.0035 x 3 + 1e-9) m x 1e3
}

TEST(SessionCsvTest, StoreExportIsTheTraineesSessionsInListOrder) {
  TempDir dir;
  const auto store = OpenSessionStore((dir.path() / "sessions.sqlite").string());
  for (int i : {3, 0, 2}) store->Add(SampleRecord(i, "ana"));
  store->Add(SampleRecord(1, "ben"));
  std::ostringstream out;
  store->ExportCsv("ana", out);
  const auto rows = ReadCsv(out.str());
  const auto listed = store->List("ana");
  ASSERT_EQ(rows.size(), 1 + listed.size());
  ASSERT_EQ(listed.size(), 3u);
  for (std::size_t i = 0; i < listed.size(); ++i) ExpectRowIs(rows[i + 1], listed[i]);
  // Oldest first: the learning curve reads top to bottom.
  EXPECT_EQ(rows[1][4], FormatUtcIso8601(SampleRecord(0).started_unix_s));
  EXPECT_EQ(rows[3][4], FormatUtcIso8601(SampleRecord(3).started_unix_s));
}

}  // namespace
}  // namespace vesica::app
