#include "app/history/history_window.h"

#include <gtest/gtest.h>

#include <QComboBox>
#include <QFile>
#include <QLabel>
#include <QPushButton>
#include <QTableWidget>
#include <QTest>
#include <sstream>

#include "app/history/learning_curve_plot.h"
#include "app/history/metrics_panel.h"
#include "history_test_support.h"

namespace vesica::app {
namespace {

using testing::AnaSessions;
using testing::BenSessions;
using testing::FlakyStore;
using testing::KnownStore;
using testing::TempDir;

std::vector<double> PlottedY(const HistoryWindow& window) {
  std::vector<double> y;
  for (const QPointF& p : window.Plot()->Points()) y.push_back(p.y());
  return y;
}

std::vector<double> PlottedX(const HistoryWindow& window) {
  std::vector<double> x;
  for (const QPointF& p : window.Plot()->Points()) x.push_back(p.x());
  return x;
}

QString Cell(const HistoryWindow& window, int row, int column) {
  const QTableWidgetItem* item = window.Table()->item(row, column);
  return item ? item->text() : QStringLiteral("<empty>");
}

QString ReadFile(const QString& path) {
  QFile file(path);
  if (!file.open(QIODevice::ReadOnly)) return QStringLiteral("<cannot read %1>").arg(path);
  return QString::fromUtf8(file.readAll());
}

std::string StoreCsv(SessionStore& store, const std::string& trainee) {
  std::ostringstream out;
  store.ExportCsv(trainee, out);
  return out.str();
}

class HistoryWindowTest : public ::testing::Test {
 protected:
  TempDir dir_;
  std::unique_ptr<SessionStore> store_ = KnownStore(dir_.path());
  QString Path(const char* name) const { return QString::fromStdString((dir_.path() / name).string()); }
};

TEST_F(HistoryWindowTest, ListsTraineesAndPlotsTheFirstInStartOrder) {
  HistoryWindow window(*store_);
  ASSERT_EQ(window.TraineeChooser()->count(), 2);
  EXPECT_EQ(window.TraineeChooser()->itemText(0), "ana");
  EXPECT_EQ(window.TraineeChooser()->itemText(1), "ben");
  EXPECT_EQ(window.CurrentTrainee(), "ana");
  EXPECT_EQ(window.Plot()->Metric().key, std::string_view("duration_s"));
  // ana's sessions were added 2nd, 3rd, 1st; the curve follows the start times.
  EXPECT_EQ(PlottedX(window), (std::vector<double>{1, 2, 3}));
  EXPECT_EQ(PlottedY(window), (std::vector<double>{900.0, 720.0, 480.5}));
  ASSERT_EQ(window.Sessions().size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) EXPECT_EQ(window.Sessions()[i].record, AnaSessions()[i]) << i;
  EXPECT_FALSE(window.StatusIsError());
  EXPECT_EQ(window.StatusText(), "3 session(s) of ana in " + QString::fromStdString(store_->Describe()));
  EXPECT_TRUE(window.ExportButton()->isEnabled());
}

TEST_F(HistoryWindowTest, ChoosingAnotherMetricReplots) {
  HistoryWindow window(*store_);
  ASSERT_TRUE(window.SelectMetric("slips"));
  EXPECT_EQ(window.MetricChooser()->currentIndex(), FindPlotMetric("slips"));
  EXPECT_EQ(PlottedY(window), (std::vector<double>{7, 4, 1}));
  // Through the chooser, as a user would.
  window.MetricChooser()->setCurrentIndex(FindPlotMetric("max_force_N"));
  EXPECT_EQ(PlottedY(window), (std::vector<double>{6.75, 5.5, 4.25}));
  window.MetricChooser()->setCurrentIndex(FindPlotMetric("tissue_removed_fraction"));
  EXPECT_EQ(PlottedY(window), (std::vector<double>{62.5, 75.0, 87.5}));
  EXPECT_FALSE(window.SelectMetric("success"));
  EXPECT_FALSE(window.SelectMetric("nonsense"));
  EXPECT_EQ(window.Plot()->Metric().key, std::string_view("tissue_removed_fraction"));
}

TEST_F(HistoryWindowTest, ChoosingAnotherTraineeReplotsAndRefillsTheTable) {
  HistoryWindow window(*store_);
  window.SelectMetric("slips");
  window.show();
  ASSERT_TRUE(QTest::qWaitForWindowExposed(&window));
  // Keyboard on the trainee chooser: Down moves to "ben".
  window.TraineeChooser()->setFocus();
  QTest::keyClick(window.TraineeChooser(), Qt::Key_Down);
  EXPECT_EQ(window.CurrentTrainee(), "ben");
  EXPECT_EQ(PlottedY(window), (std::vector<double>{2, 9}));
  EXPECT_EQ(window.Table()->rowCount(), 2);
  EXPECT_EQ(Cell(window, 0, 4), "20:00");
  EXPECT_EQ(Cell(window, 1, 6), "9");
  EXPECT_EQ(window.StatusText().left(23), "2 session(s) of ben in ");

  ASSERT_TRUE(window.SelectTrainee("ana"));
  EXPECT_EQ(PlottedY(window), (std::vector<double>{7, 4, 1}));
  EXPECT_EQ(window.Table()->rowCount(), 3);
  EXPECT_FALSE(window.SelectTrainee("carl"));
  EXPECT_TRUE(window.StatusIsError());
  EXPECT_EQ(window.StatusText(), "Error: trainee 'carl' has no sessions");
  EXPECT_EQ(window.CurrentTrainee(), "ana");
}

TEST_F(HistoryWindowTest, TableRowsHoldTheSessionValues) {
  HistoryWindow window(*store_);
  QTableWidget* table = window.Table();
  ASSERT_EQ(table->rowCount(), 3);
  ASSERT_EQ(table->columnCount(), 14);  // the last three: the Calot step's (calot_history_test.cpp)
  EXPECT_EQ(table->horizontalHeaderItem(1)->text(), "Started (UTC)");
  EXPECT_EQ(table->horizontalHeaderItem(2)->text(), "Procedure");
  EXPECT_EQ(table->horizontalHeaderItem(8)->text(), QString::fromUtf8("Liver damage (mm²)"));
  const QStringList first = {"1",     "2026-11-23 03:20", "Cholecystectomy", "cholecystectomy-default",
                             "15:00", "no",               "7",               "575.0",
                             "40.0",  "6.75",             "62.5"};
  const QStringList last = {"3",     "2026-11-25 03:20", "Cholecystectomy", "cholecystectomy-default",
                            "08:01", "yes",              "1",               "275.0",
                            "5.0",   "4.25",             "87.5"};
  for (int column = 0; column < 11; ++column) {
    EXPECT_EQ(Cell(window, 0, column), first[column]) << "column " << column;
    EXPECT_EQ(Cell(window, 2, column), last[column]) << "column " << column;
  }
  EXPECT_EQ(Cell(window, 1, 5), "no");
  EXPECT_EQ(Cell(window, 1, 4), "12:00");
}

TEST_F(HistoryWindowTest, SelectedRowShowsInTheMetricsPanel) {
  HistoryWindow window(*store_);
  // The newest session is selected first.
  EXPECT_EQ(window.Table()->currentRow(), 2);
  EXPECT_EQ(window.SelectedSession()->ValueText("metric_success"), "yes (gallbladder free, no perforation)");
  EXPECT_EQ(window.SelectedSession()->ValueText("metric_duration"), "08:01");
  window.show();
  ASSERT_TRUE(QTest::qWaitForWindowExposed(&window));
  QTableWidget* table = window.Table();
  const QRect cell = table->visualItemRect(table->item(0, 0));
  QTest::mouseClick(table->viewport(), Qt::LeftButton, {}, cell.center());
  EXPECT_EQ(table->currentRow(), 0);
  EXPECT_EQ(window.SelectedSession()->ValueText("metric_success"), "no (not free, perforated)");
  EXPECT_EQ(window.SelectedSession()->ValueText("metric_slips"), "7");
  EXPECT_EQ(window.SelectedSession()->ValueText("metric_liver_damage"), QString::fromUtf8("40.0 mm²"));
  EXPECT_EQ(window.SelectedSession()->ValueText("metric_springs_cut"), "70 / 86");
  table->selectRow(1);
  EXPECT_EQ(window.SelectedSession()->ValueText("metric_success"), "no (perforated)");
}

TEST_F(HistoryWindowTest, BiopsiesAreListedBesideCholecystectomiesAndPlottedOnTheirOwnCurves) {
  SessionRecord biopsy = AnaSessions()[2];
  biopsy.procedure = Procedure::kNeedleBiopsy;
  biopsy.scenario = "liver-biopsy";
  biopsy.started_unix_s += 3600;
  biopsy.ended_unix_s = biopsy.started_unix_s + 240;
  biopsy.metrics = {};
  biopsy.metrics.duration_s = 240;
  biopsy.metrics.max_force_N = 3.5;
  biopsy.metrics.success = true;
  biopsy.metrics.biopsy_sampled = true;
  biopsy.metrics.time_to_sample_s = 185;
  biopsy.metrics.sample_distance_m = 0.0072;
  biopsy.metrics.nogo_crossings = 1;
  biopsy.metrics.insertion_attempts = 2;
  store_->Add(biopsy);
  HistoryWindow window(*store_);
  ASSERT_EQ(window.Table()->rowCount(), 4);
  EXPECT_EQ(Cell(window, 3, 2), "Needle biopsy");
  EXPECT_EQ(Cell(window, 3, 3), "liver-biopsy");
  EXPECT_EQ(Cell(window, 3, 4), "04:00");
  EXPECT_EQ(Cell(window, 3, 6), QString::fromUtf8("–"));  // slips: no measure of a biopsy
  EXPECT_EQ(Cell(window, 3, 9), "3.50");
  // The newest (the biopsy) is selected: the panel shows the biopsy's rows, not the cholecystectomy's.
  const MetricsPanel* panel = window.SelectedSession();
  EXPECT_EQ(panel->ValueText("metric_success"), "yes (good specimen)");
  EXPECT_EQ(panel->ValueText("metric_time_to_sample"), "03:05");
  EXPECT_EQ(panel->ValueText("metric_sample_distance"), "7.2 mm");
  EXPECT_EQ(panel->ValueText("metric_specimen"), "good specimen");
  EXPECT_EQ(panel->ValueText("metric_nogo_crossings"), "1");
  EXPECT_EQ(panel->ValueText("metric_insertion_attempts"), "2");
  EXPECT_TRUE(panel->RowShown("metric_time_to_sample"));
  EXPECT_FALSE(panel->RowShown("metric_slips"));
  window.Table()->selectRow(0);
  EXPECT_FALSE(panel->RowShown("metric_time_to_sample"));
  EXPECT_TRUE(panel->RowShown("metric_slips"));
  // The cholecystectomy's duration curve holds its three sessions only; the biopsy its own.
  EXPECT_EQ(PlottedY(window), (std::vector<double>{900.0, 720.0, 480.5}));
  ASSERT_TRUE(window.SelectMetric("time_to_sample_s"));
  EXPECT_EQ(PlottedY(window), (std::vector<double>{185.0}));
  ASSERT_TRUE(window.SelectMetric("sample_distance_m"));
  EXPECT_DOUBLE_EQ(PlottedY(window).at(0), 7.2);
  ASSERT_TRUE(window.SelectMetric("duration_s"));
  EXPECT_EQ(PlottedY(window).size(), 3u);
}

TEST_F(HistoryWindowTest, ExportCsvToWritesTheTraineesRows) {
  HistoryWindow window(*store_);
  const QString path = Path("ana.csv");
  ASSERT_TRUE(window.ExportCsvTo(path)) << window.StatusText().toStdString();
  EXPECT_FALSE(window.StatusIsError());
  EXPECT_EQ(window.StatusText(), "Exported 3 session(s) of ana to " + path);
  const QString csv = ReadFile(path);
  EXPECT_EQ(csv.toStdString(), StoreCsv(*store_, "ana"));
  const QStringList lines = csv.split('\n', Qt::SkipEmptyParts);
  ASSERT_EQ(lines.size(), 4);
  EXPECT_TRUE(
      lines[0].startsWith("id,trainee_id,scenario,station,started_utc,ended_utc,input_recording_path,"
                          "replay,unfinished,physics_lag_s,procedure,duration_s,"));
  // Rows in start order; ana's were stored as ids 4, 1, 3.
  EXPECT_TRUE(lines[1].startsWith("4,ana,cholecystectomy-default,station-1,2026-11-23T03:20:00Z,"))
      << lines[1].toStdString();
  EXPECT_TRUE(lines[2].startsWith("1,ana,cholecystectomy-default,station-1,2026-11-24T03:20:00Z,"))
      << lines[2].toStdString();
  EXPECT_TRUE(
      lines[3].startsWith("3,ana,cholecystectomy-default,station-1,2026-11-25T03:20:00Z,"
                          "2026-11-25T03:28:30Z,\"/recordings/ana, third.vrec\",0,0,0,cholecystectomy,480.5,150,125,1,60,"))
      << lines[3].toStdString();
  // ... springs, free, perforation, success, the biopsy's five and the Calot step's fourteen (none).
  EXPECT_TRUE(lines[3].endsWith(",86,86,1,0,1,0,0,0,0,0" + QString(",0").repeated(14)));

  ASSERT_TRUE(window.SelectTrainee("ben"));
  ASSERT_TRUE(window.ExportCsvTo(Path("ben.csv")));
  EXPECT_EQ(ReadFile(Path("ben.csv")).toStdString(), StoreCsv(*store_, "ben"));
  EXPECT_EQ(ReadFile(Path("ben.csv")).count('\n'), 3);
}

TEST_F(HistoryWindowTest, ExportToAnUnwritablePathFailsInTheStatusLabel) {
  HistoryWindow window(*store_);
  const QString path = Path("no-such-folder/ana.csv");
  EXPECT_FALSE(window.ExportCsvTo(path));
  EXPECT_TRUE(window.StatusIsError());
  EXPECT_TRUE(window.StatusText().startsWith("Error: export CSV to " + path + ": "))
      << window.StatusText().toStdString();
  EXPECT_FALSE(QFile::exists(path));
  EXPECT_EQ(window.StatusLabel()->objectName(), "status_label");
  EXPECT_EQ(window.StatusLabel()->text(), window.StatusText());
}

TEST_F(HistoryWindowTest, StoreErrorWhileListingTraineesShowsInTheStatusLabel) {
  FlakyStore flaky(*store_);
  flaky.fail_list_trainees = true;
  HistoryWindow window(flaky);
  EXPECT_TRUE(window.StatusIsError());
  EXPECT_EQ(window.StatusText(), "Error: session database test.sqlite: list trainees: disk I/O error");
  EXPECT_EQ(window.TraineeChooser()->count(), 0);
  EXPECT_TRUE(window.Plot()->Points().empty());
  EXPECT_EQ(window.Table()->rowCount(), 0);
  EXPECT_FALSE(window.ExportButton()->isEnabled());
  EXPECT_FALSE(window.ExportCsvTo(Path("x.csv")));
  EXPECT_EQ(window.StatusText(), "Error: export CSV: no trainee selected");
  EXPECT_FALSE(QFile::exists(Path("x.csv")));

  // The store recovers: Reload shows it.
  flaky.fail_list_trainees = false;
  EXPECT_TRUE(window.Reload());
  EXPECT_FALSE(window.StatusIsError());
  EXPECT_EQ(window.TraineeChooser()->count(), 2);
  EXPECT_EQ(PlottedY(window), (std::vector<double>{900.0, 720.0, 480.5}));
}

TEST_F(HistoryWindowTest, StoreErrorWhileListingSessionsKeepsTheWindowUsable) {
  FlakyStore flaky(*store_);
  HistoryWindow window(flaky);
  ASSERT_EQ(window.Table()->rowCount(), 3);
  ASSERT_TRUE(window.ExportCsvTo(Path("before.csv")));
  const QString before = ReadFile(Path("before.csv"));

  flaky.fail_list = true;
  EXPECT_FALSE(window.SelectTrainee("ben"));
  EXPECT_TRUE(window.StatusIsError());
  EXPECT_EQ(window.StatusText(), "Error: session database test.sqlite: list sessions: disk I/O error");
  EXPECT_TRUE(window.Plot()->Points().empty());
  EXPECT_EQ(window.Plot()->EmptyText(), "Could not read the sessions of ben");
  EXPECT_EQ(window.Table()->rowCount(), 0);
  EXPECT_EQ(window.SelectedSession()->ValueText("metric_slips"), QString::fromUtf8("–"));
  // ExportCsv lists through the store too: the failed export leaves the old file as it was.
  EXPECT_FALSE(window.ExportCsvTo(Path("before.csv")));
  EXPECT_EQ(window.StatusText(), "Error: export CSV: session database test.sqlite: list sessions: disk I/O error");
  EXPECT_EQ(ReadFile(Path("before.csv")), before);

  flaky.fail_list = false;
  EXPECT_TRUE(window.SelectTrainee("ben"));
  EXPECT_FALSE(window.StatusIsError());
  EXPECT_EQ(window.Table()->rowCount(), 2);
}

TEST_F(HistoryWindowTest, EmptyStoreShowsTheEmptyState) {
  TempDir empty_dir;
  auto empty = OpenSessionStore((empty_dir.path() / "empty.sqlite").string());
  HistoryWindow window(*empty);
  EXPECT_FALSE(window.StatusIsError());
  EXPECT_EQ(window.StatusText(), "No sessions recorded in " + QString::fromStdString(empty->Describe()));
  EXPECT_EQ(window.TraineeChooser()->count(), 0);
  EXPECT_FALSE(window.TraineeChooser()->isEnabled());
  EXPECT_EQ(window.CurrentTrainee(), "");
  EXPECT_TRUE(window.Plot()->Points().empty());
  EXPECT_EQ(window.Plot()->EmptyText(), "No sessions recorded yet");
  EXPECT_EQ(window.Table()->rowCount(), 0);
  EXPECT_FALSE(window.ExportButton()->isEnabled());

  // A session arrives; Reload picks it up.
  empty->Add(BenSessions()[0]);
  EXPECT_TRUE(window.Reload());
  EXPECT_EQ(window.CurrentTrainee(), "ben");
  EXPECT_EQ(PlottedY(window), (std::vector<double>{1200.0}));
}

TEST_F(HistoryWindowTest, ReloadKeepsTheSelectedTrainee) {
  HistoryWindow window(*store_);
  ASSERT_TRUE(window.SelectTrainee("ben"));
  SessionRecord third = BenSessions()[1];
  third.started_unix_s += 86400;
  third.ended_unix_s += 86400;
  third.metrics.duration_s = 600;
  store_->Add(third);
  EXPECT_TRUE(window.Reload());
  EXPECT_EQ(window.CurrentTrainee(), "ben");
  EXPECT_EQ(PlottedY(window), (std::vector<double>{1200.0, 1000.0, 600.0}));
  EXPECT_EQ(window.Table()->rowCount(), 3);
}

TEST_F(HistoryWindowTest, OwningConstructorAndObjectNames) {
  auto window = std::make_unique<HistoryWindow>(KnownStore(dir_.path() / "owned"));
  EXPECT_EQ(window->CurrentTrainee(), "ana");
  for (const char* name : {"trainee_combo", "metric_combo", "learning_curve", "sessions_table", "metrics_panel",
                           "export_csv_button", "status_label"})
    EXPECT_NE(window->findChild<QWidget*>(QString::fromLatin1(name)), nullptr) << name;
  EXPECT_EQ(window->ExportButton()->text(), "Export CSV...");
  EXPECT_THROW(HistoryWindow(std::unique_ptr<SessionStore>()), std::invalid_argument);
}

}  // namespace
}  // namespace vesica::app
