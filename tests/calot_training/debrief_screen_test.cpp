// The debrief screen rendered offscreen (QT_QPA_PLATFORM=offscreen): its text after the
// critical error and after a passed case, and that it draws something.

#include "app/calot/debrief_screen.h"

#include <gtest/gtest.h>

#include <QImage>
#include <QLabel>
#include <QPixmap>
#include <QPushButton>
#include <cstdlib>
#include <set>

#include "tests/calot_training/scripted_case.h"

namespace vesica::app::calot {
namespace {

using testing::kCommonBileDuct;
using testing::ScriptedCase;

CalotMetrics Observed(const ScriptedCase& script) {
  CalotMetrics metrics;
  for (const CalotSnapshot& snapshot : script.snapshots()) metrics.Observe(snapshot);
  return metrics;
}

// Distinct colours in the rendered widget: a blank or unpainted screen has one or two.
int DistinctColours(DebriefScreen& screen) {
  const QImage image = screen.grab().toImage();
  std::set<QRgb> colours;
  for (int y = 0; y < image.height(); y += 2)
    for (int x = 0; x < image.width(); x += 2) colours.insert(image.pixel(x, y));
  return static_cast<int>(colours.size());
}

TEST(DebriefScreenTest, AfterTheCriticalErrorItStatesTheOutcomeTheErrorAndTheMetrics) {
  ScriptedCase script;
  script.SetDissection(0.4, 0.1);
  script.Advance(12.0);
  script.Clip(kCommonBileDuct, 0.7);
  script.Advance(0.4);
  const CalotMetrics metrics = Observed(script);
  ASSERT_TRUE(metrics.CaseEnded());

  DebriefScreen screen;
  screen.Show(metrics);
  screen.show();
  EXPECT_EQ(screen.Outcome()->text(), "Failed: bile duct injury");
  EXPECT_TRUE(screen.Reasons()->isVisible());
  EXPECT_TRUE(screen.Reasons()->text().contains(
      "Clip placed on the common bile duct at 12.4 s before the critical view of safety"));
  const QString all = screen.AllText();
  EXPECT_TRUE(all.startsWith("Calot's triangle: debrief\nFailed: bile duct injury\n")) << all.toStdString();
  EXPECT_TRUE(all.contains("Critical view of safety: not reached")) << all.toStdString();
  EXPECT_TRUE(all.contains("Clips, common bile duct: 1 (bile duct injury)")) << all.toStdString();
  EXPECT_TRUE(all.contains("Bile duct injuries: 1")) << all.toStdString();
  EXPECT_EQ(screen.findChild<QLabel*>("debrief_value_0")->text(), "12.4 s");
  EXPECT_NE(screen.findChild<QPushButton*>("debrief_close"), nullptr);
  EXPECT_GT(DistinctColours(screen), 10);
  // VESICA_DEBRIEF_PNG=path saves the rendered screen (for the docs).
  if (const char* png = std::getenv("VESICA_DEBRIEF_PNG")) {
    EXPECT_TRUE(screen.grab().save(QString::fromLocal8Bit(png)));
  }
}

TEST(DebriefScreenTest, APassedCaseSaysSoWithoutReasonsAndAShowReplacesThePrevious) {
  DebriefScreen screen;
  ScriptedCase injury;
  injury.Clip(kCommonBileDuct, 0.5);
  injury.Advance(1.0);
  screen.Show(Observed(injury));
  screen.Show(Observed(testing::CorrectDissection(testing::Variant::kArteryCrossingInFront)));
  screen.show();
  EXPECT_EQ(screen.Outcome()->text(), "Passed");
  EXPECT_FALSE(screen.Reasons()->isVisible());
  const QString all = screen.AllText();
  EXPECT_FALSE(all.contains("bile duct injury")) << all.toStdString();
  EXPECT_TRUE(all.contains("Critical view of safety: reached at 60.5 s, before the first clip")) << all.toStdString();
  EXPECT_TRUE(all.contains("Division, cystic artery (anterior to the common hepatic duct): between clips at 68.5 s"))
      << all.toStdString();
  EXPECT_EQ(all.count('\n') + 1, 2 + 9);  // title, outcome, nine metric rows
}

}  // namespace
}  // namespace vesica::app::calot
