#include "app/trainer/trainer_app.h"

#include <spdlog/spdlog.h>

#include <QStatusBar>
#include <QTimer>
#include <exception>
#include <utility>

#include "app/records/pending_sessions.h"
#include "app/records/session_store.h"
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
  if (!pending_checked_) StorePendingSessionsAtStart();
  return true;
}

void TrainerApp::StorePendingSessionsAtStart() {
  pending_checked_ = true;
  if (options_.records_location.empty()) return;
  const auto path = PendingSessionsPath(options_.records_location);
  std::error_code ignored;
  if (!std::filesystem::exists(path, ignored)) return;
  try {
    const PendingStoreResult r = StorePendingSessions(path, *OpenSessionStore(options_.records_location));
    if (r.left == 0) {
      const std::string message = "Stored " + std::to_string(r.stored) + " session(s) kept from an earlier run in " +
                                  path.string();
      spdlog::info("{}", message);
      window_->statusBar()->showMessage(QString::fromStdString(message));
    } else {
      window_->ShowError(std::to_string(r.left) + " earlier session(s) still NOT stored (" + r.error +
                         "); they wait in " + path.string());
      spdlog::error("{}", window_->last_error());
    }
  } catch (const std::exception& e) {
    window_->ShowError(std::string("earlier sessions wait in ") + path.string() + ", not stored yet: " + e.what());
    spdlog::error("{}", window_->last_error());
  }
}

void TrainerApp::Shutdown() {
  if (window_) window_->StoreUnfinishedSession();
}

}  // namespace vesica::app
