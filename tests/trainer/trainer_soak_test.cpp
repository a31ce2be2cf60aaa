// A day at an arm station in one process: the trainer replays the committed dissection 20 times
// with both emulated arms (vesica-armsim processes) connected, and one arm's process is killed
// mid-session and started again. Every session must reach the records, each the same as the
// first (no state leaks from one session into the next), the arm must come back to "ok" without
// a restart, and the process must not grow session after session.

#include <QVTKOpenGLNativeWidget.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <QStatusBar>
#include <QTest>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "app/records/session_store.h"
#include "app/render/scene_meshes.h"
#include "app/scenario/scenario_loader.h"
#include "app/session/dissection_setup.h"
#include "app/trainer/trainer_window.h"
#include "tests/device/armsim_process.h"

namespace vesica::app {
namespace {

constexpr int kSessions = 20;
constexpr int kKilledInSession = 10;  // 1-based: the session during which the left arm's process dies
// Growth of the resident set from the end of the second session to the end of the last. Measured
// 2026-11-27 (release, Xvfb/llvmpipe): see the test's output; the bound leaves room for the
// allocator's and the GL driver's caches, not for a leak of a session's state (a scene snapshot
// is ~10 MB, so 18 leaked sessions would be far above it).
constexpr double kRssGrowthBoundMiB = 60.0;

double ResidentMiB() {
  std::ifstream status("/proc/self/status");
  std::string key;
  while (status >> key) {
    if (key == "VmRSS:") {
      double kib = 0;
      status >> kib;
      return kib / 1024.0;
    }
    status.ignore(1 << 12, '\n');
  }
  return -1;
}

std::string ArmLine(const TrainerWindow& w, const std::string& arm) {
  const std::string lines = w.ArmStatusLines() + "\n";
  const size_t at = lines.find(arm + ":");
  return at == std::string::npos ? std::string() : lines.substr(at, lines.find('\n', at) - at);
}

class Armsim {
 public:
  Armsim(int node_id, int base_port) : node_id_(node_id), base_port_(base_port) {}
  bool Start() {
    process_ = std::make_unique<device::testing::ArmsimProcess>();
    const int port = base_port_ + 2 * (node_id_ - 1);
    return process_->Start(VESICA_ARMSIM_PATH, {"--node-id", std::to_string(node_id_), "--local-port",
                                                std::to_string(port), "--remote-port", std::to_string(port + 1),
                                                "--hand", "hold", "--log-level", "warn"});
  }
  void Crash() {
    process_->Kill(SIGKILL);
    process_->Finish(nullptr);
    process_.reset();
  }

 private:
  int node_id_, base_port_;
  std::unique_ptr<device::testing::ArmsimProcess> process_;
};

TEST(TrainerSoakTest, TwentyReplaysWithTheArmsConnectedAndAnArmCrashLoseNothingAndDoNotGrow) {
  const std::filesystem::path source(VESICA_SOURCE_DIR);
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("vesica_trainer_soak_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const Scenario scenario = LoadScenario(source / "data/scenarios/cholecystectomy-arms.toml");
  const SceneMeshes meshes = LoadSceneMeshes(scenario);
  const auto model = BuildDissectionModelFor(scenario, meshes);
  const std::filesystem::path recording = source / "data/recordings/dissection.csv";

  const int base = device::testing::FreeArmBasePort();
  ASSERT_NE(base, 0);
  Armsim left(1, base), right(2, base);
  ASSERT_TRUE(left.Start());
  ASSERT_TRUE(right.Start());

  TrainerOptions options;
  options.trainee_id = "soak";
  options.records_location = (dir / "sessions.sqlite").string();
  options.recordings_dir = dir / "recordings";
  options.replay_file = recording;
  options.real_time = false;  // as fast as the physics goes: 20 x 31 s of dissection in minutes
  options.arms_udp_base_port = base;
  auto w = std::make_unique<TrainerWindow>(scenario, std::make_unique<LaparoscopeView>(scenario, meshes), model,
                                           options);
  w->resize(400, 225);  // small: the soak is about sessions and arms, software rendering is slow
  w->show();

  double rss_after_second = -1, rss_last = -1;
  const auto start = std::chrono::steady_clock::now();
  bool saw_loss = false;
  for (int session = 1; session <= kSessions; ++session) {
    if (session > 1) {
      ASSERT_TRUE(w->StartSession(TrainerWindow::InputChoice::kReplay, recording)) << w->last_error();
    }
    EXPECT_TRUE(w->statusBar()->currentMessage().contains("haptic arms connected"))
        << w->statusBar()->currentMessage().toStdString();
    if (session == 1) {
      ASSERT_TRUE(QTest::qWaitFor([&] { return ArmLine(*w, "left arm") == "left arm: ok" &&
                                                ArmLine(*w, "right arm") == "right arm: ok"; },
                                  60000))
          << w->ArmStatusLines();
    }
    if (session == kKilledInSession) {
      left.Crash();
      saw_loss = QTest::qWaitFor([&] { return ArmLine(*w, "left arm").find("ok") == std::string::npos; }, 10000);
      EXPECT_TRUE(saw_loss) << "the dead arm is not shown: " << w->ArmStatusLines();
      EXPECT_EQ(ArmLine(*w, "right arm"), "right arm: ok");
      ASSERT_TRUE(left.Start());
      EXPECT_TRUE(QTest::qWaitFor([&] { return ArmLine(*w, "left arm") == "left arm: ok"; }, 30000))
          << "the restarted arm did not come back: " << w->ArmStatusLines();
    }
    ASSERT_TRUE(QTest::qWaitFor([&] { return w->stored_session_id().has_value(); }, 600000))
        << "session " << session << " not stored: " << w->last_error() << "\nstatus: "
        << w->statusBar()->currentMessage().toStdString() << "\nloops:\n" << w->LoopRatesSummary()
        << "\narms:\n" << w->ArmStatusLines();
    if (session == 2) rss_after_second = ResidentMiB();
    rss_last = ResidentMiB();
    std::printf("session %2d stored after %.0f s, resident set %.1f MiB, arms: %s\n", session,
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), rss_last,
                w->ArmStatusLines().c_str());
    std::fflush(stdout);
  }
  EXPECT_TRUE(w->last_error().empty()) << w->last_error();
  EXPECT_EQ(ArmLine(*w, "left arm"), "left arm: ok");
  EXPECT_EQ(ArmLine(*w, "right arm"), "right arm: ok");
  const double growth = rss_last - rss_after_second;
  std::printf("resident set: %.1f MiB after session 2, %.1f MiB after session %d (growth %.1f MiB)\n",
              rss_after_second, rss_last, kSessions, growth);
  EXPECT_LT(growth, kRssGrowthBoundMiB);
  w.reset();

  // Every session is in the records, as a finished replay, and each is the first one again.
  auto store = OpenSessionStore(options.records_location);
  const auto sessions = store->List("soak");
  ASSERT_EQ(sessions.size(), static_cast<size_t>(kSessions));
  const SessionRecord& first = sessions.front().record;
  EXPECT_GT(first.metrics.springs_cut, 0);
  for (const auto& s : sessions) {
    const SessionRecord& r = s.record;
    EXPECT_TRUE(r.replay);
    EXPECT_FALSE(r.unfinished);
    EXPECT_EQ(r.metrics.springs_cut, first.metrics.springs_cut);
    EXPECT_EQ(r.metrics.gallbladder_free, first.metrics.gallbladder_free);
    EXPECT_DOUBLE_EQ(r.metrics.duration_s, first.metrics.duration_s);
    EXPECT_DOUBLE_EQ(r.metrics.path_length_left_m, first.metrics.path_length_left_m);
    EXPECT_DOUBLE_EQ(r.metrics.path_length_right_m, first.metrics.path_length_right_m);
    EXPECT_DOUBLE_EQ(r.metrics.cautery_on_s, first.metrics.cautery_on_s);
    EXPECT_FALSE(r.input_recording_path.empty());
  }
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace vesica::app
