#include "app/trainer/trainer_app.h"

#include <spdlog/spdlog.h>

#include <QTimer>
#include <exception>
#include <utility>

#include "app/render/laparoscope_view.h"
#include "app/render/scene_meshes.h"
#include "app/scenario/scenario_loader.h"
#include "app/session/dissection_setup.h"

namespace vesica::app {

TrainerApp::TrainerApp(TrainerOptions options, QSize window_size)
    : options_(std::move(options)), window_size_(window_size) {}

TrainerApp::~TrainerApp() = default;

bool TrainerApp::Open(const std::filesystem::path& scenario_path) {
  std::unique_ptr<TrainerWindow> next;
  try {
    const Scenario scenario = LoadScenario(scenario_path);
    const SceneMeshes meshes = LoadSceneMeshes(scenario);
    spdlog::info("scenario '{}': liver {} nodes, gallbladder {} nodes / {} tets", scenario.name,
                 meshes.liver.num_vertices(), meshes.gallbladder.num_vertices(), meshes.gallbladder.num_tets());
    auto view = std::make_unique<LaparoscopeView>(scenario, meshes);
    spdlog::info("building the dissection scene (the liver's Green's functions are cached after the first run)");
    auto model = BuildDissectionModelFor(scenario, meshes);
    spdlog::info("{} connective-tissue springs; records: {}", model->tissue.springs.size(),
                 options_.records_location.empty() ? "not stored" : options_.records_location);
    // The old session ends and is stored before the new one starts, so the two never overlap in
    // the records and the old one's physics threads are gone.
    if (window_) window_->EndAndStoreSession();
    next = std::make_unique<TrainerWindow>(scenario, std::move(view), std::move(model), options_);
  } catch (const std::exception& e) {
    last_error_ = e.what();
    spdlog::error("{}", last_error_);
    if (window_) window_->ShowError(last_error_);
    return false;
  }
  last_error_.clear();
  options_.replay_file.clear();
  // Called from the old window's menu: replace it once that call has returned.
  next->SetScenarioOpener(
      [this](const std::filesystem::path& path) { QTimer::singleShot(0, &deferred_, [this, path] { Open(path); }); });
  next->resize(window_size_);
  if (window_) next->move(window_->pos());
  window_ = std::move(next);
  window_->show();
  return true;
}

}  // namespace vesica::app
