#include "app/trainer/trainer_app.h"

#include <spdlog/spdlog.h>

#include <QStatusBar>
#include <QTimer>
#include <exception>
#include <utility>

#include "app/biopsy/liver_motion.h"
#include "app/needle_mode/patient_view.h"
#include "app/records/pending_sessions.h"
#include "app/records/session_store.h"
#include "app/render/laparoscope_view.h"
#include "app/render/scene_meshes.h"
#include "app/scenario/scenario_loader.h"
#include "app/session/dissection_setup.h"
#include "device/stylus/keyboard_stylus.h"
#include "device/stylus/udp_stylus.h"

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
    if (needle_window_) {  // back from the needle mode: the stylus gets zero force and is released
      needle_window_->EndAndStoreSession();
      needle_window_.reset();
    }
    next = std::make_unique<TrainerWindow>(scenario, std::move(view), std::move(model), options_);
  } catch (const std::exception& e) {
    last_error_ = e.what();
    spdlog::error("{}", last_error_);
    if (window_) window_->ShowError(last_error_);
    return false;
  }
  last_error_.clear();
  options_.replay_file.clear();
  scenario_path_ = scenario_path;
  ConnectOpeners(*next);
  next->resize(window_size_);
  if (window_) next->move(window_->pos());
  window_ = std::move(next);
  window_->show();
  if (!pending_checked_) StorePendingSessionsAtStart();
  return true;
}

void TrainerApp::ConnectOpeners(TrainerWindow& window) {
  // Called from the old window's menu: replace it once that call has returned.
  window.SetScenarioOpener(
      [this](const std::filesystem::path& path) { QTimer::singleShot(0, &deferred_, [this, path] { Open(path); }); });
  window.SetNeedleBiopsyOpener([this] { QTimer::singleShot(0, &deferred_, [this] { OpenNeedleBiopsy(); }); });
}

bool TrainerApp::OpenNeedleBiopsy() {
  std::unique_ptr<needle_mode::NeedleWindow> next;
  try {
    if (!biopsy_patient_) {
      const std::filesystem::path dir =
          options_.patient_dir.empty() ? std::filesystem::path(VESICA_DATA_DIR) / "patients" : options_.patient_dir;
      spdlog::info("loading the biopsy patient from {} and meshing its organs", dir.string());
      auto loaded = biopsy::LoadCommittedBiopsyPatient(dir);
      biopsy_surfaces_ = patient::MeshPatient(loaded->volume.labels, needle_mode::DisplayMeshing());
      biopsy_patient_ = std::move(loaded);
    }
    std::shared_ptr<device::StylusDevice> stylus;
    std::function<void()> servo;
    if (options_.omni_udp_port > 0) {
      device::UdpStylusConfig config;
      config.device = {"127.0.0.1", static_cast<std::uint16_t>(options_.omni_udp_port)};
      config.local = {"127.0.0.1", static_cast<std::uint16_t>(options_.omni_udp_port + 1)};
      auto udp = std::make_shared<device::UdpStylus>(config);
      if (udp->Open() == device::DeviceStatus::kTransportError)
        throw std::runtime_error("Omni emulator on UDP port " + std::to_string(options_.omni_udp_port + 1) + ": " +
                                 udp->last_error());
      servo = [udp] { udp->Tick(); };
      stylus = udp;
    } else {
      const Eigen::Vector3d tumour = biopsy_patient_->model->liver.tumour_centre_m;
      auto keyboard = std::make_shared<device::KeyboardStylus>(
          biopsy::StartingStylus(biopsy::PlacementAtRightSide(tumour), tumour));
      keyboard->Open();
      stylus = keyboard;
    }
    // The arms get zero force and are released (the window's arm bridge closes them) before the
    // stylus takes over; the cholecystectomy is stored first (unfinished when it had begun).
    if (window_) {
      window_->StoreUnfinishedSession();
      window_.reset();
    }
    needle_mode::NeedleModeOptions options;
    options.trainee_id = options_.trainee_id;
    options.station = options_.station;
    options.records_location = options_.records_location;
    options.recordings_dir = options_.recordings_dir;
    options.saver = options_.saver;
    if (!options_.liver_motion.empty()) {
      options.liver_motion =
          biopsy::LoadLiverMotion(*biopsy_patient_, options_.liver_motion_mesh, options_.liver_motion);
      spdlog::info("needle mode: the liver breathes as registered in {}", options_.liver_motion.string());
    }
    next = std::make_unique<needle_mode::NeedleWindow>(biopsy_patient_, biopsy_surfaces_, stylus, servo, options);
  } catch (const std::exception& e) {
    last_error_ = e.what();
    spdlog::error("needle biopsy: {}", last_error_);
    if (window_) window_->ShowError("needle biopsy: " + last_error_);
    return false;
  }
  last_error_.clear();
  next->SetProcedureSwitcher([this] {
    QTimer::singleShot(0, &deferred_,
                       [this] { Open(scenario_path_.empty() ? DefaultScenarioPath() : scenario_path_); });
  });
  next->resize(window_size_);
  needle_window_ = std::move(next);
  needle_window_->show();
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
      const std::string message =
          "Stored " + std::to_string(r.stored) + " session(s) kept from an earlier run in " + path.string();
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
  if (needle_window_) needle_window_->EndAndStoreSession();
}

}  // namespace vesica::app
