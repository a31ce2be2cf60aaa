// vesica-trainer: the laparoscopic cholecystectomy trainer. Runs a dissection session of a
// scenario in a window (keyboard or a recorded session drives the instruments; the finished
// session is stored in the records database), or renders the scene at rest off-screen to a PNG
// (--headless; vesica-replay runs whole sessions headless).

#include <QVTKOpenGLNativeWidget.h>
#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <QApplication>
#include <QSurfaceFormat>
#include <QTimer>
#include <cstdlib>
#include <exception>
#include <filesystem>

#include "app/records/default_location.h"
#include "app/records/session_store.h"
#include "app/render/laparoscope_view.h"
#include "app/render/scene_meshes.h"
#include "app/scenario/scenario_loader.h"
#include "app/trainer/quit_on_signal.h"
#include "app/trainer/records_at_start.h"
#include "app/trainer/trainer_app.h"
#include "device/input/input_recording.h"

int main(int argc, char** argv) {
  CLI::App cli{"Vesica laparoscopic cholecystectomy trainer"};
  std::string scenario_path = vesica::app::DefaultScenarioPath().string();
  bool headless = false;
  int frames = 3, width = 1280, height = 720, quit_after_ms = 0;
  std::string screenshot = "vesica.png", grab, grab_window;
  cli.add_option("-s,--scenario", scenario_path, "scenario file (TOML)")->capture_default_str();
  cli.add_flag("--headless", headless, "render off-screen and write a PNG instead of opening a window");
  cli.add_option("--frames", frames, "frames to render in headless mode")->check(CLI::PositiveNumber);
  cli.add_option("--screenshot", screenshot, "PNG written in headless mode")->capture_default_str();
  cli.add_option("--width", width, "image width in pixels")->check(CLI::Range(64, 8192));
  cli.add_option("--height", height, "image height in pixels")->check(CLI::Range(64, 8192));
  cli.add_option("--quit-after-ms", quit_after_ms, "close the window after this many ms (tests, demos)");
  cli.add_option("--grab", grab, "with --quit-after-ms: save a PNG of the laparoscope view before closing");
  cli.add_option("--grab-window", grab_window, "with --quit-after-ms: save a PNG of the whole window before closing");
  vesica::app::TrainerOptions options;
  if (const char* user = std::getenv("USER"); user != nullptr && *user != '\0') options.trainee_id = user;
  std::string replay, records = "default", recordings_dir = "default";
  bool fast = false;
  cli.add_option("--trainee", options.trainee_id, "trainee id the session is stored under")->capture_default_str();
  cli.add_option("--replay", replay, "drive both instruments from a recorded session (docs/recording.md)");
  cli.add_flag("--fast", fast, "with --replay: run the physics as fast as it goes instead of in real time");
  cli.add_option("--records", records,
                 "where finished sessions are stored: SQLite file or PostgreSQL connection string; 'default' = "
                 "$VESICA_RECORDS_DB, else $XDG_DATA_HOME/vesica/sessions.sqlite; 'none' = not stored")
      ->capture_default_str();
  cli.add_option("--recordings-dir", recordings_dir,
                 "where each session's input is saved ('default' = next to the records database, 'none')")
      ->capture_default_str();
  std::string procedure = "cholecystectomy";
  cli.add_option("--procedure", procedure, "the procedure to start in (Session > Procedure switches at run time)")
      ->check(CLI::IsMember({"cholecystectomy", "needle_biopsy"}))
      ->capture_default_str();
  cli.add_option("--omni-udp-port", options.omni_udp_port,
                 "needle mode: the Omni emulator's port (vesica-omnisim --port P; it sends poses to P + 1); "
                 "default: the keyboard and mouse drive the needle")
      ->check(CLI::Range(1, 65534));
  cli.add_option("--patient-dir", options.patient_dir, "needle mode: the biopsy patient's files (default data/patients)");
  auto* motion_mesh = cli.add_option("--liver-motion-mesh", options.liver_motion_mesh,
                                     "needle mode: the tet mesh vesica-register registered (.vtu)");
  cli.add_option("--liver-motion", options.liver_motion,
                 "needle mode: vesica-register's displacement.csv on that mesh: the liver breathes as registered "
                 "instead of by ChainMail")
      ->needs(motion_mesh);
  cli.add_option("--arms-udp-base-port", options.arms_udp_base_port,
                 "emulated arms: vesica-armsim node n listens on this port + 2(n-1)")
      ->capture_default_str()
      ->check(CLI::Range(1, 65535 - 253));
  CLI11_PARSE(cli, argc, argv);

  if (headless) {
    try {
      const auto scenario = vesica::app::LoadScenario(scenario_path);
      vesica::app::LaparoscopeView view(scenario, vesica::app::LoadSceneMeshes(scenario));
      vesica::app::RenderToPng(view, width, height, frames, screenshot);
      spdlog::info("wrote {} ({}x{}, {} frames)", screenshot, width, height, frames);
      return 0;
    } catch (const std::exception& e) {
      spdlog::error("{}", e.what());
      return 2;
    }
  }

  try {
    if (records == "default") records = vesica::app::DefaultSessionStoreLocation();
    if (records != "none") options.records_location = records;
    if (recordings_dir == "default") {
      const std::filesystem::path db(records);
      options.recordings_dir = records != "none" && !vesica::app::IsConnectionString(records)
                                   ? db.parent_path() / "recordings"
                                   : std::filesystem::path();
    } else if (recordings_dir != "none") {
      options.recordings_dir = recordings_dir;
    }
    // Now, not when the first session ends: a location that cannot hold the records is an error.
    if (!options.records_location.empty()) {
      const std::string warning = vesica::app::CheckRecordsLocationAtStart(options.records_location);
      if (!warning.empty()) spdlog::warn("{}", warning);
    }
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    return 2;
  }
  if (!replay.empty()) {
    // Read before any window opens: a recording that cannot be replayed ends the program with the
    // reason, rather than a session that silently falls back to the keyboard.
    try {
      vesica::device::ReadInputRecording(replay);
    } catch (const std::exception& e) {
      spdlog::error("--replay: recording rejected: {}", e.what());
      return 2;
    }
  }
  options.replay_file = replay;
  options.real_time = !fast;

  QSurfaceFormat::setDefaultFormat([] {
    auto format = QVTKOpenGLNativeWidget::defaultFormat();
    format.setSamples(0);
    return format;
  }());
  QApplication app(argc, argv);
  vesica::app::QuitOnTerminationSignals(app);
  vesica::app::TrainerApp trainer(options, QSize(width, height));
  if (!trainer.Open(scenario_path)) return 2;  // the error is logged
  if (procedure == "needle_biopsy" && !trainer.OpenNeedleBiopsy()) return 2;
  if (quit_after_ms > 0) {
    QTimer::singleShot(quit_after_ms, &app, [&] {
      QMainWindow* window = trainer.window() ? static_cast<QMainWindow*>(trainer.window())
                                             : static_cast<QMainWindow*>(trainer.needle_window());
      if (window != nullptr) {
        if (!grab.empty() && !window->centralWidget()->grab().save(QString::fromStdString(grab)))
          spdlog::error("could not save {}", grab);
        if (!grab_window.empty() && !window->grab().save(QString::fromStdString(grab_window)))
          spdlog::error("could not save {}", grab_window);
      }
      app.quit();
    });
  }
  const int status = app.exec();
  trainer.Shutdown();  // SIGTERM, Quit or --quit-after-ms mid-session: stored as unfinished
  if (trainer.window() != nullptr)
    spdlog::info("loop rates ({}x{} window):\n{}", width, height, trainer.window()->LoopRatesSummary());
  return status;
}
