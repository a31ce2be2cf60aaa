// vesica-trainer: the laparoscopic cholecystectomy trainer. Opens the laparoscope view of a
// scenario in a window, or renders it off-screen to a PNG (--headless).

#include <CLI/CLI.hpp>
#include <QApplication>
#include <QSurfaceFormat>
#include <QTimer>
#include <QVTKOpenGLNativeWidget.h>
#include <spdlog/spdlog.h>

#include <exception>
#include <memory>

#include "app/render/laparoscope_view.h"
#include "app/scenario/scenario_loader.h"
#include "app/trainer/trainer_window.h"

int main(int argc, char** argv) {
  CLI::App cli{"Vesica laparoscopic cholecystectomy trainer"};
  std::string scenario_path = vesica::app::DefaultScenarioPath().string();
  bool headless = false;
  int frames = 3, width = 1280, height = 720, quit_after_ms = 0;
  std::string screenshot = "vesica.png", grab;
  cli.add_option("-s,--scenario", scenario_path, "scenario file (TOML)")->capture_default_str();
  cli.add_flag("--headless", headless, "render off-screen and write a PNG instead of opening a window");
  cli.add_option("--frames", frames, "frames to render in headless mode")->check(CLI::PositiveNumber);
  cli.add_option("--screenshot", screenshot, "PNG written in headless mode")->capture_default_str();
  cli.add_option("--width", width, "image width in pixels")->check(CLI::Range(64, 8192));
  cli.add_option("--height", height, "image height in pixels")->check(CLI::Range(64, 8192));
  cli.add_option("--quit-after-ms", quit_after_ms, "close the window after this many ms (tests, demos)");
  cli.add_option("--grab", grab, "with --quit-after-ms: save a PNG of the laparoscope view before closing");
  CLI11_PARSE(cli, argc, argv);

  std::unique_ptr<vesica::app::LaparoscopeView> view;
  vesica::app::Scenario scenario;
  try {
    scenario = vesica::app::LoadScenario(scenario_path);
    const auto meshes = vesica::app::LoadSceneMeshes(scenario);
    spdlog::info("scenario '{}': liver {} nodes, gallbladder {} nodes / {} tets", scenario.name,
                 meshes.liver.num_vertices(), meshes.gallbladder.num_vertices(), meshes.gallbladder.num_tets());
    view = std::make_unique<vesica::app::LaparoscopeView>(scenario, meshes);
    if (headless) {
      vesica::app::RenderToPng(*view, width, height, frames, screenshot);
      spdlog::info("wrote {} ({}x{}, {} frames)", screenshot, width, height, frames);
      return 0;
    }
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    return 2;
  }

  QSurfaceFormat::setDefaultFormat([] {
    auto format = QVTKOpenGLNativeWidget::defaultFormat();
    format.setSamples(0);
    return format;
  }());
  QApplication app(argc, argv);
  vesica::app::TrainerWindow window(scenario, std::move(view));
  window.resize(width, height);
  window.show();
  if (quit_after_ms > 0) {
    QTimer::singleShot(quit_after_ms, &window, [&] {
      if (!grab.empty() && !window.centralWidget()->grab().save(QString::fromStdString(grab))) spdlog::error("could not save {}", grab);
      app.quit();
    });
  }
  return app.exec();
}
