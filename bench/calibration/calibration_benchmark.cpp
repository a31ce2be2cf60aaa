// What a technician waits for: vesica-calibrate's whole calibration of both emulated arms
// (in-process, bus time instead of wall time), and the report it writes at the end. The wall
// time is the host's cost of simulating the arms and running the procedures; `bus_s` is how long
// the same calibration keeps real arms busy.
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <filesystem>
#include <string>

#include "app/calibrate/calibration_report.h"
#include "app/calibrate/calibration_run.h"
#include "app/calibrate/commands.h"
#include "app/calibrate/exit_codes.h"
#include "app/calibrate/open_arm.h"

namespace vesica::app::calibrate {
namespace {

constexpr std::uint64_t kSeed = 7;  // the sample report's arms (docs/calibration.md)

std::string ScratchDir(const char* name) {
  return (std::filesystem::temp_directory_path() /
          ("vesica_calibration_bench_" + std::to_string(::getpid()) + "_" + name))
      .string();
}

ToolOptions Emulated(const std::string& dir) {
  ToolOptions o;
  o.bus.kind = BusSpec::Kind::kEmulated;
  o.bus.emulated_seed = kSeed;
  o.data_dir = dir;
  o.command = "calibrate";
  o.date_s = 1790000000;
  return o;
}

// Both arms from blank flash, each calibrated, checked, saved and reported, as
// `vesica-calibrate --emulated 7 --yes calibrate 1` and then `... 2`.
void BM_TwoArmCalibration(benchmark::State& state) {
  const std::string dir = ScratchDir("two_arms");
  double bus_s = 0.0, report_s = 0.0;
  for (auto _ : state) {
    state.PauseTiming();
    std::filesystem::remove_all(dir);
    state.ResumeTiming();
    SilentUi ui;
    ToolSession session(Emulated(dir), ui, nullptr);
    for (int arm = 1; arm <= 2; ++arm) {
      const CommandOutcome o = Calibrate(session, arm, CalibrateRequest{});
      if (o.exit_code != kExitOk) {
        state.SkipWithError(("arm " + std::to_string(arm) + ": " + o.text).c_str());
        return;
      }
      bus_s += o.json["bus_time_s"].get<double>();
      report_s += o.json["report_write_s"].get<double>();
    }
  }
  state.counters["bus_s"] = benchmark::Counter(bus_s, benchmark::Counter::kAvgIterations);
  state.counters["report_s"] = benchmark::Counter(report_s, benchmark::Counter::kAvgIterations);
  std::filesystem::remove_all(dir);
}
BENCHMARK(BM_TwoArmCalibration)->Unit(benchmark::kSecond)->UseRealTime()->Iterations(3);

// One arm's report as calibrate writes it: JSON, HTML and the two PNG plots.
class ReportFixture : public benchmark::Fixture {
 public:
  void SetUp(const benchmark::State&) override {
    if (session_) return;
    dir_ = ScratchDir("report");
    std::filesystem::remove_all(dir_);
    session_ = std::make_unique<ToolSession>(Emulated(dir_), ui_, nullptr);
    CommandOutcome failure;
    if (!OpenArm(*session_, 1, &arm_, &failure)) {
      error_ = failure.text;
      return;
    }
    const StoredImage before = ReadStoredCalibration(*arm_.link, arm_.info);
    RunRequest run;
    run.plan.date_s = 1790000000;
    run.plan.tool_version = kToolVersion;
    run.save = false;
    run.judge = [](const device::calibration::CalibrationResult& r, const std::vector<Step>& steps) {
      return AcceptanceChecks(r, 0b111, steps);
    };
    outcome_ = RunCalibration(*arm_.link, *session_->ObserverOf(1), run);
    if (outcome_.result.abort != device::calibration::AbortReason::kNone) error_ = outcome_.result.message;
    input_.arm = 1;
    input_.info = arm_.info;
    input_.before = ValuesOf(before.params);
    input_.run = &outcome_;
    input_.state = "pre-operational";
    input_.bus = session_->where(1);
    input_.date_s = 1790000000;
  }
  void TearDown(const benchmark::State&) override {}
  ~ReportFixture() override {
    session_.reset();
    if (!dir_.empty()) std::filesystem::remove_all(dir_);
  }

 protected:
  std::string dir_, error_;
  SilentUi ui_;
  std::unique_ptr<ToolSession> session_;
  OpenedArm arm_;
  RunOutcome outcome_;
  ReportInput input_;
};

BENCHMARK_DEFINE_F(ReportFixture, BM_WriteReport)(benchmark::State& state) {
  if (!error_.empty()) {
    state.SkipWithError(error_.c_str());
    return;
  }
  const std::string out = dir_ + "/reports";
  std::filesystem::create_directories(out);
  for (auto _ : state) {
    nlohmann::json doc = nlohmann::json::object();
    ReportFiles files;
    std::string error;
    if (!WriteReport(input_, out, "arm1-calibrate", doc, &files, &error)) {
      state.SkipWithError(error.c_str());
      return;
    }
  }
}
BENCHMARK_REGISTER_F(ReportFixture, BM_WriteReport)->Unit(benchmark::kMillisecond)->UseRealTime();

// The HTML page alone, from the report's JSON (no plots, nothing written).
BENCHMARK_DEFINE_F(ReportFixture, BM_ReportHtml)(benchmark::State& state) {
  if (!error_.empty()) {
    state.SkipWithError(error_.c_str());
    return;
  }
  const nlohmann::json doc = ReportJson(input_);
  for (auto _ : state) benchmark::DoNotOptimize(ReportHtml(doc));
}
BENCHMARK_REGISTER_F(ReportFixture, BM_ReportHtml)->Unit(benchmark::kMicrosecond)->UseRealTime();

}  // namespace
}  // namespace vesica::app::calibrate
