// Each scripted outcome of the Calot step goes into a session record, through an SQLite store
// and the CSV export, and reads back as it was measured.

#include "app/calot/calot_session_metrics.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <sstream>

#include "app/records/sqlite_session_store.h"
#include "tests/calot_training/scripted_case.h"
#include "tests/records/csv_reader.h"
#include "tests/records/temp_dir.h"

namespace vesica::app::calot {
namespace {

using testing::kCommonBileDuct;
using testing::kCysticArtery;
using testing::kCysticDuct;
using testing::ScriptedCase;

SessionMetrics Measured(const ScriptedCase& script) {
  CalotMetrics metrics;
  for (const CalotSnapshot& snapshot : script.snapshots()) metrics.Observe(snapshot);
  SessionMetrics session;
  session.duration_s = metrics.time_s();
  StoreCalotMetrics(metrics, session);
  return session;
}

ScriptedCase ClipBeforeView(testing::Variant variant = testing::Variant::kStandard) {
  ScriptedCase script(variant);
  script.SetDissection(0.5, 0.2);
  script.Advance(10.0);
  script.Clip(kCysticDuct, 0.3);
  script.Advance(1.0);
  script.ReachCriticalView();
  return script;
}

ScriptedCase UnclippedArteryCut(testing::Variant variant = testing::Variant::kStandard) {
  ScriptedCase script(variant);
  script.ReachCriticalView();
  script.Cut(kCysticArtery, script.planned_cut_s(kCysticArtery));
  script.Advance(1.0);
  return script;
}

ScriptedCase BileDuctClipped(testing::Variant variant = testing::Variant::kStandard) {
  ScriptedCase script(variant);
  script.ReachCriticalView();
  script.Clip(kCommonBileDuct, 0.4);
  script.Advance(1.0);
  return script;
}

TEST(CalotSessionMetricsTest, ACorrectDissectionFillsEveryColumn) {
  const SessionMetrics m = Measured(testing::CorrectDissection(testing::Variant::kStandard));
  EXPECT_TRUE(m.calot_step);
  EXPECT_TRUE(m.cvs_achieved);
  EXPECT_DOUBLE_EQ(m.cvs_time_s, 60.5);
  EXPECT_TRUE(m.cvs_before_first_clip);
  EXPECT_EQ(m.cystic_duct_clips, 3);
  EXPECT_EQ(m.cystic_artery_clips, 3);
  EXPECT_TRUE(m.cystic_duct_clips_correct);
  EXPECT_TRUE(m.cystic_artery_clips_correct);
  EXPECT_TRUE(m.cystic_duct_divided_between_clips);
  EXPECT_TRUE(m.cystic_artery_divided_between_clips);
  EXPECT_EQ(m.bleeding_events, 0);
  EXPECT_EQ(m.bile_leaks, 0);
  EXPECT_EQ(m.bile_duct_injuries, 0);
  EXPECT_TRUE(m.calot_passed);
}

TEST(CalotSessionMetricsTest, EachFailureShowsInItsColumns) {
  const SessionMetrics early = Measured(ClipBeforeView());
  EXPECT_TRUE(early.cvs_achieved);
  EXPECT_DOUBLE_EQ(early.cvs_time_s, 11.5);
  EXPECT_FALSE(early.cvs_before_first_clip);
  EXPECT_EQ(early.cystic_duct_clips, 1);
  EXPECT_FALSE(early.cystic_duct_clips_correct);
  EXPECT_FALSE(early.calot_passed);

  const SessionMetrics bleed = Measured(UnclippedArteryCut());
  EXPECT_EQ(bleed.bleeding_events, 1);
  EXPECT_EQ(bleed.cystic_artery_clips, 0);
  EXPECT_FALSE(bleed.cystic_artery_divided_between_clips);
  EXPECT_FALSE(bleed.calot_passed);

  const SessionMetrics injury = Measured(BileDuctClipped());
  EXPECT_EQ(injury.bile_duct_injuries, 1);
  EXPECT_TRUE(injury.cvs_before_first_clip);  // the view came first; the clip went on the wrong duct
  EXPECT_FALSE(injury.calot_passed);
}

TEST(CalotSessionMetricsTest, EachOutcomeOfEachVariantIsStoredAndReadBackFromSqliteAndTheCsv) {
  vesica::app::testing::TempDir dir("vesica-calot");
  SqliteSessionStore store(dir.path() / "sessions.sqlite");
  std::vector<SessionRecord> records;
  for (const testing::Variant variant : testing::kAllVariants) {
    const ScriptedCase scripts[] = {testing::CorrectDissection(variant), ClipBeforeView(variant),
                                    UnclippedArteryCut(variant), BileDuctClipped(variant)};
    for (const ScriptedCase& script : scripts) {
      SessionRecord r;
      r.trainee_id = "resident-1";
      r.scenario = std::string("calot-") + testing::VariantName(variant);
      r.started_unix_s = 1795406400 + 600 * static_cast<std::int64_t>(records.size());
      r.ended_unix_s = r.started_unix_s + 120;
      r.metrics = Measured(script);
      records.push_back(r);
      store.Add(r);
    }
  }
  const auto stored = store.List("resident-1");
  ASSERT_EQ(stored.size(), records.size());
  for (std::size_t i = 0; i < records.size(); ++i) EXPECT_EQ(stored[i].record, records[i]) << "session " << i;

  std::ostringstream csv;
  store.ExportCsv("resident-1", csv);
  const auto rows = vesica::app::testing::ReadCsv(csv.str());
  ASSERT_EQ(rows.size(), 1 + records.size());
  const auto column = [&](const std::string& name) {
    const auto it = std::find(rows[0].begin(), rows[0].end(), name);
    EXPECT_NE(it, rows[0].end()) << name;
    return static_cast<std::size_t>(it - rows[0].begin());
  };
  const std::size_t passed = column("calot_passed"), injuries = column("bile_duct_injuries"),
                    bleeds = column("bleeding_events"), before = column("cvs_before_first_clip"),
                    cvs_time = column("cvs_time_s"), step = column("calot_step");
  // Four sessions a variant, in the scripts' order: passed, clipped early, bled, bile duct injury.
  for (std::size_t v = 0; v < std::size(testing::kAllVariants); ++v) {
    const auto& row = [&](std::size_t outcome) -> const std::vector<std::string>& { return rows[1 + 4 * v + outcome]; };
    for (std::size_t outcome = 0; outcome < 4; ++outcome) EXPECT_EQ(row(outcome)[step], "1");
    EXPECT_EQ(row(0)[passed], "1") << v;
    EXPECT_EQ(row(0)[cvs_time], "60.5") << v;
    EXPECT_EQ(row(1)[before], "0") << v;
    EXPECT_EQ(row(1)[passed], "0") << v;
    EXPECT_EQ(row(2)[bleeds], "1") << v;
    EXPECT_EQ(row(2)[passed], "0") << v;
    EXPECT_EQ(row(3)[injuries], "1") << v;
    EXPECT_EQ(row(3)[passed], "0") << v;
  }
}

}  // namespace
}  // namespace vesica::app::calot
