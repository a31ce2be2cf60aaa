// vesica-replay: runs a recorded two-handed session through the dissection scene without a
// window and prints the trainee's metrics; optionally writes a PNG sequence of the laparoscope
// view (needs an X display: run under xvfb-run on a headless machine). A recorded needle biopsy
// (a stylus recording, docs/omni.md) runs through the biopsy session on the breathing patient
// instead and prints the biopsy's metrics; the file's first line says which procedure it is.
//   vesica-replay [-s SCENARIO] RECORDING [--png-dir DIR --png-every-s 0.5]
//   vesica-replay RECORDING [--procedure needle_biopsy] [--patient-dir data/patients]
// The recording's "# scenario:" line must name the scenario given (--any-scenario overrides).
// Progress goes to stderr: a line redrawn in place on a terminal, else (logs, CI) a line at each
// tenth of a replay of more than kPlainProgressMinSteps steps.

#include <spdlog/spdlog.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <exception>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "app/biopsy/biopsy_patient.h"
#include "app/biopsy/biopsy_replay.h"
#include "app/biopsy/liver_motion.h"
#include "app/records/procedure.h"
#include "app/render/laparoscope_view.h"
#include "app/render/scene_meshes.h"
#include "app/replay/session_replay.h"
#include "app/replay/state_digest.h"
#include "app/scenario/scenario_loader.h"
#include "app/session/dissection_setup.h"
#include "device/input/input_recording.h"
#include "device/input/recording_error.h"
#include "device/stylus/stylus_recording.h"
#include "physics/scene/dissection_settings.h"

namespace {

/// Replays shorter than this (10 s at 5 ms) print no plain progress lines: they end soon enough.
constexpr long kPlainProgressMinSteps = 2000;

enum class ProgressStyle { kAuto, kLines, kNone };

/// Reports how far a replay has got on stderr, in one of two forms: on a terminal a line redrawn
/// in place at most every 0.2 s of wall time; otherwise plain lines at each tenth, which a CI log
/// keeps readable.
class ReplayProgress {
 public:
  /// `session_s`: the session time the replay ends at (steps times h).
  ReplayProgress(ProgressStyle style, long total_steps, double session_s)
      : total_steps_(total_steps), session_s_(session_s) {
    if (style == ProgressStyle::kAuto)
      style = isatty(STDERR_FILENO)                   ? ProgressStyle::kAuto
              : total_steps >= kPlainProgressMinSteps ? ProgressStyle::kLines
                                                      : ProgressStyle::kNone;
    live_ = style == ProgressStyle::kAuto;
    lines_ = style == ProgressStyle::kLines;
  }
  ~ReplayProgress() { Finish(); }
  ReplayProgress(const ReplayProgress&) = delete;
  ReplayProgress& operator=(const ReplayProgress&) = delete;

  /// Ends the redrawn line, so that what follows starts on a line of its own.
  void Finish() {
    if (live_ && drawn_) std::fputc('\n', stderr);
    drawn_ = false;
  }

  /// After step `step` (1-based) at session time `time_s` since the recording's start.
  void Update(long step, double time_s) {
    const int tenth = static_cast<int>(10 * step / total_steps_);
    if (lines_ && tenth > last_tenth_) {
      last_tenth_ = tenth;
      std::fprintf(stderr, "replay progress: %3d%% (%.3f of %.3f s)\n", 10 * tenth, time_s, session_s_);
    }
    if (!live_) return;
    const auto now = std::chrono::steady_clock::now();
    if (step != total_steps_ && drawn_ && now - last_drawn_ < std::chrono::milliseconds(200)) return;
    last_drawn_ = now;
    drawn_ = true;
    std::fprintf(stderr, "\rreplaying: %.3f of %.3f s (%3d%%)", time_s, session_s_,
                 static_cast<int>(100 * step / total_steps_));
    std::fflush(stderr);
  }

 private:
  long total_steps_;
  double session_s_;
  bool live_ = false, lines_ = false, drawn_ = false;
  int last_tenth_ = 0;
  std::chrono::steady_clock::time_point last_drawn_{};
};

// The procedure a recording is of, from its first line; nullopt when it is neither format.
std::optional<vesica::app::Procedure> RecordedProcedure(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::string first;
  std::getline(in, first);
  if (first == vesica::device::kStylusRecordingMagic) return vesica::app::Procedure::kNeedleBiopsy;
  if (first == vesica::device::kRecordingMagic) return vesica::app::Procedure::kCholecystectomy;
  return std::nullopt;
}

int ReplayNeedleBiopsy(const std::string& recording_path, const std::string& patient_dir,
                       const std::string& liver_motion_mesh, const std::string& liver_motion, ProgressStyle style) {
  namespace biopsy = vesica::app::biopsy;
  const auto recording = vesica::device::ReadStylusRecording(recording_path);
  const auto patient = biopsy::LoadCommittedBiopsyPatient(patient_dir);
  biopsy::BiopsySessionSettings settings;
  if (!liver_motion.empty()) {
    settings.liver_motion = biopsy::LoadLiverMotion(*patient, liver_motion_mesh, liver_motion);
    spdlog::info("the liver breathes as registered in {} (on {})", liver_motion, liver_motion_mesh);
  }
  const double span_s = recording.samples.back().time_s - recording.samples.front().time_s;
  spdlog::info("needle biopsy: patient {}, recording {:.2f} s ({} samples)", patient_dir, span_s,
               recording.samples.size());
  const long ticks = std::lround(span_s / 0.001) + 1;
  ReplayProgress progress(style, ticks / 5, span_s);  // counted in 5 ms steps, as a dissection's
  const biopsy::BiopsyReplayResult r = biopsy::ReplayBiopsy(
      patient, recording, settings, 0.001, [&](long tick, long) { progress.Update(tick / 5, static_cast<double>(tick) * 1e-3); });
  progress.Finish();
  const vesica::app::SessionMetrics& m = r.metrics;
  std::printf("procedure             needle biopsy\n");
  std::printf("session time          %.3f s (%ld haptic ticks)\n", r.duration_s, r.ticks);
  if (m.biopsy_sampled) {
    const auto& sample = *r.needle_metrics.sample;
    std::printf("time to sample        %.3f s\n", m.time_to_sample_s);
    std::printf("sample to tumour      %.2f mm: %s\n", m.sample_distance_m * 1e3,
                std::string(vesica::physics::PrecisionName(sample.precision)).c_str());
  } else {
    std::printf("time to sample        - (no sample taken)\n");
  }
  std::printf("insertion attempts    %d\n", m.insertion_attempts);
  std::printf("no-go crossings       %d", m.nogo_crossings);
  for (int k = 0; k < vesica::physics::kNoGoKinds; ++k) {
    const auto kind = static_cast<vesica::physics::NoGo>(k);
    if (r.needle_metrics.crossings(kind) > 0)
      std::printf(" (%s %d)", std::string(vesica::physics::NoGoName(kind)).c_str(), r.needle_metrics.crossings(kind));
  }
  std::printf("\nmax force             %.3f N (mean inside the body %.3f N)\n", m.max_force_N, m.mean_force_N);
  std::printf("success               %s\n", m.success ? "yes" : "no");
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App cli{"Vesica: replay a recorded dissection headless and print the trainee metrics"};
  std::string scenario_path = vesica::app::DefaultScenarioPath().string();
  std::string recording_path, png_dir;
  double png_every_s = 0.5;
  int width = 640, height = 360;
  bool trace = false;
  double slow_step_ms = 0;
  bool real_time = false;
  cli.add_option("recording", recording_path, "input recording (docs/recording.md)")->required();
  cli.add_option("-s,--scenario", scenario_path, "scenario file (TOML)")->capture_default_str();
  cli.add_option("--png-dir", png_dir, "write the laparoscope view as PNGs into this folder");
  cli.add_option("--png-every-s", png_every_s, "session time between PNGs")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cli.add_option("--width", width, "PNG width in pixels")->check(CLI::Range(64, 4096));
  cli.add_option("--height", height, "PNG height in pixels")->check(CLI::Range(64, 4096));
  cli.add_flag("--trace", trace, "print one line per physics step (contacts, forces, energy) to stderr");
  cli.add_flag("--real-time", real_time,
               "pace the steps to the clock as the trainer does (background work then gets the time it has there)");
  cli.add_option("--slow-steps", slow_step_ms, "list the steps whose wall time exceeds this many ms (to stderr)")
      ->check(CLI::PositiveNumber);
  bool any_scenario = false;
  cli.add_flag("--any-scenario", any_scenario,
               "replay even when the recording's '# scenario:' line names another scenario than the one given");
  std::string progress = "auto";
  cli.add_option("--progress", progress,
                 "progress on stderr: auto (redrawn on a terminal; otherwise a line each tenth of a replay longer "
                 "than 10 s), lines (a line each tenth), none")
      ->check(CLI::IsMember({"auto", "lines", "none"}))
      ->capture_default_str();
  std::string procedure = "auto";
  cli.add_option("--procedure", procedure,
                 "the procedure the recording must be of: auto (from its first line), cholecystectomy, needle_biopsy")
      ->check(CLI::IsMember({"auto", "cholecystectomy", "needle_biopsy"}))
      ->capture_default_str();
  std::string patient_dir = std::string(VESICA_DATA_DIR) + "/patients";
  cli.add_option("--patient-dir", patient_dir, "a needle biopsy's patient (the synthetic patient's files)")
      ->capture_default_str();
  std::string liver_motion_mesh, liver_motion;
  auto* motion_mesh_option = cli.add_option("--liver-motion-mesh", liver_motion_mesh,
                                            "needle biopsy: the tet mesh vesica-register registered (.vtu)");
  cli.add_option("--liver-motion", liver_motion,
                 "needle biopsy: vesica-register's displacement.csv on that mesh: the liver breathes as registered "
                 "instead of by ChainMail")
      ->needs(motion_mesh_option);
  CLI11_PARSE(cli, argc, argv);

  try {
    const auto recorded = RecordedProcedure(recording_path);
    if (recorded && procedure != "auto" && procedure != vesica::app::ProcedureKey(*recorded)) {
      spdlog::error("{}: is a recording of a {}, not of a {} (--procedure {})", recording_path,
                    vesica::app::ProcedureKey(*recorded), procedure, procedure);
      return 2;
    }
    if (recorded == vesica::app::Procedure::kNeedleBiopsy) {
      const ProgressStyle style = progress == "lines"  ? ProgressStyle::kLines
                                  : progress == "none" ? ProgressStyle::kNone
                                                       : ProgressStyle::kAuto;
      return ReplayNeedleBiopsy(recording_path, patient_dir, liver_motion_mesh, liver_motion, style);
    }
    vesica::device::ReplayInput input(vesica::device::ReadInputRecording(recording_path));
    try {  // refused before anything is built: the span alone decides
      vesica::app::ReplayStepCount(input.duration_s(), vesica::physics::DissectionSettings{}.time_step_s);
    } catch (const std::out_of_range& e) {
      spdlog::error("recording rejected: {}: {}", recording_path, e.what());
      return 2;
    }
    const vesica::app::Scenario scenario = vesica::app::LoadScenario(scenario_path);
    // Checked before the minutes of model building: a recording made in another scenario replays
    // other anatomy and other ports, and its metrics would mean nothing.
    const std::string& recorded_in = input.recording().scenario_name;
    if (recorded_in.empty()) {
      spdlog::warn("{}: has no '# scenario:' line; replaying it in '{}'", recording_path, scenario.name);
    } else if (recorded_in != scenario.name) {
      if (!any_scenario) {
        spdlog::error(
            "{}: recorded in scenario '{}', but {} is '{}': give the scenario it was recorded in with -s, or "
            "--any-scenario to replay it in this one",
            recording_path, recorded_in, scenario_path, scenario.name);
        return 2;
      }
      spdlog::warn("{}: recorded in scenario '{}', replayed in '{}' (--any-scenario)", recording_path, recorded_in,
                   scenario.name);
    }
    const vesica::app::SceneMeshes meshes = vesica::app::LoadSceneMeshes(scenario);
    const auto model = vesica::app::BuildDissectionModelFor(scenario, meshes);
    const long total_steps = vesica::app::ReplayStepCount(input.duration_s(), model->settings.time_step_s);
    spdlog::info(
        "scenario '{}': liver {} nodes, gallbladder {} nodes, {} springs, {} membrane elements; recording {:.2f} s",
        scenario.name, model->liver->num_nodes(), model->gallbladder->rest_mesh.num_vertices(),
        model->tissue.springs.size(), model->tissue.membrane.triangles.rows(), input.duration_s());
    // A scenario with Calot's triangle replays its step too (the trainer runs it the same way).
    vesica::app::DissectionSession session(model, vesica::app::DefaultCauteryParams(),
                                           vesica::app::CalotSessionSetupFor(scenario, double(width) / height));

    std::unique_ptr<vesica::app::LaparoscopeView> view;
    if (!png_dir.empty()) {
      std::filesystem::create_directories(png_dir);
      view = std::make_unique<vesica::app::LaparoscopeView>(scenario, meshes);
    }
    int png_index = 0;
    double next_png_s = 0;
    const auto paced_from = std::chrono::steady_clock::now();
    const ProgressStyle progress_style = progress == "lines"  ? ProgressStyle::kLines
                                         : progress == "none" ? ProgressStyle::kNone
                                                              : ProgressStyle::kAuto;
    ReplayProgress progress_report(progress_style, total_steps,
                                   static_cast<double>(total_steps) * model->settings.time_step_s);
    long steps_done = 0;
    const vesica::app::ReplayOutcome outcome =
        vesica::app::RunReplay(session, input, [&](const vesica::app::DissectionSession& s, const auto& r) {
          progress_report.Update(++steps_done, s.time_s());
          if (real_time)
            std::this_thread::sleep_until(paced_from + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                                           std::chrono::duration<double>(s.time_s())));
          if (trace) {
            std::fprintf(stderr,
                         "t %.3f it %d rows %d touch %d/%d gap %.2e/%.2e f %.3f/%.3f grasp %d mem %zu cut %d E %.3e\n",
                         s.time_s(), r.physics.gallbladder_solver_iterations, r.physics.constraint_rows,
                         static_cast<int>(r.physics.touches[0].surface), static_cast<int>(r.physics.touches[1].surface),
                         r.physics.touches[0].gap_m, r.physics.touches[1].gap_m, r.physics.tool_force_N[0].norm(),
                         r.physics.tool_force_N[1].norm(), static_cast<int>(s.scene().grasp().state()),
                         r.physics.touches[1].membrane_elements.size(), r.springs_cut, s.scene().Energy());
          }
          if (!view || s.time_s() + 1e-9 < next_png_s) return;
          view->Update(s.MakeRenderFrame());
          char name[32];
          std::snprintf(name, sizeof name, "frame_%05d.png", png_index++);
          vesica::app::RenderToPng(*view, width, height, 1, std::filesystem::path(png_dir) / name);
          next_png_s += png_every_s;
        });

    progress_report.Finish();
    const vesica::app::SessionMetrics m = session.metrics();
    std::printf("session time          %.3f s (%ld steps)\n", m.duration_s, outcome.steps);
    std::printf("gallbladder free      %s", m.gallbladder_free ? "yes" : "no");
    if (outcome.gallbladder_free_at_s >= 0) std::printf(" (at %.3f s)", outcome.gallbladder_free_at_s);
    std::printf("\nsprings cut           %d of %d\n", m.springs_cut, m.springs_total);
    std::printf("tissue removed        %.1f %%\n", 100.0 * m.tissue_removed_fraction);
    std::printf("slips                 %d\n", m.slips);
    std::printf("cautery on            %.3f s\n", m.cautery_on_s);
    std::printf("liver damage          %.2f mm^2\n", m.liver_damage_m2 * 1e6);
    std::printf("gallbladder damage    %.2f mm^2%s\n", m.gallbladder_damage_m2 * 1e6,
                m.perforation ? " (perforated)" : "");
    std::printf("max force             %.3f N (mean in contact %.3f N)\n", m.max_force_N, m.mean_force_N);
    std::printf("path length           left %.3f m, right %.3f m\n", m.path_length_left_m, m.path_length_right_m);
    std::printf("success               %s\n", m.success ? "yes" : "no");
    std::printf("finite                %s\n", outcome.finite ? "yes" : "no");
    std::printf("max energy            %.6g J\n", outcome.max_energy_J);
    std::printf("rejected fem steps    %ld\n", outcome.rejected_fem_steps);
    if (slow_step_ms > 0)
      for (size_t k = 0; k < outcome.step_wall_ms.size(); ++k)
        if (outcome.step_wall_ms[k] > slow_step_ms)
          std::fprintf(stderr, "slow step at %.3f s: %.2f ms\n",
                       static_cast<double>(k + 1) * model->settings.time_step_s, outcome.step_wall_ms[k]);
    if (!outcome.step_wall_ms.empty()) {
      std::vector<double> sorted = outcome.step_wall_ms;
      std::sort(sorted.begin(), sorted.end());
      const auto quantile = [&](double q) {
        return sorted[static_cast<size_t>(q * static_cast<double>(sorted.size() - 1))];
      };
      const auto slowest = std::max_element(outcome.step_wall_ms.begin(), outcome.step_wall_ms.end());
      std::printf("step wall time        median %.2f ms, p99 %.2f ms, max %.2f ms (step at %.3f s); h = %.1f ms\n",
                  quantile(0.5), quantile(0.99), *slowest,
                  static_cast<double>(slowest - outcome.step_wall_ms.begin() + 1) * model->settings.time_step_s,
                  1e3 * model->settings.time_step_s);
    }
    std::printf("state digest          %s\n", vesica::app::FormatDigest(vesica::app::StateDigest(session)).c_str());
    if (view) std::printf("pngs                  %d in %s\n", png_index, png_dir.c_str());
    return outcome.finite ? 0 : 3;
  } catch (const vesica::device::RecordingError& e) {
    spdlog::error("recording rejected: {}", e.what());
    return 2;
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    return 2;
  }
}
