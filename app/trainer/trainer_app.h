#pragma once
// The trainer's top level: owns the window of the open scenario and replaces it when the
// resident opens another one (Session > Open scenario...). The running session is ended and
// stored first; a scenario that does not load leaves the open one running, with the error shown.

#include <QObject>
#include <QSize>
#include <filesystem>
#include <memory>
#include <string>

#include "app/biopsy/biopsy_patient.h"
#include "app/needle_mode/needle_window.h"
#include "app/patient/patient_meshing.h"
#include "app/trainer/trainer_window.h"

namespace vesica::app {

class TrainerApp {
 public:
  /// `options.replay_file` drives only the first scenario opened; later ones take their input
  /// from the scenario (keyboard, arms or its own replay).
  TrainerApp(TrainerOptions options, QSize window_size);
  ~TrainerApp();
  TrainerApp(const TrainerApp&) = delete;
  TrainerApp& operator=(const TrainerApp&) = delete;

  /// Loads the scenario, its meshes and the dissection model (seconds; the liver's Green's
  /// functions come from the cache after the first run) and shows it in a new window. Returns
  /// false when it fails to load: last_error() names the file and what is wrong, and the window
  /// open before (if any) goes on as it was. The first window that opens also stores the
  /// sessions left in the pending file by an earlier run, and says so in its status bar.
  bool Open(const std::filesystem::path& scenario_path);

  /// Switches to the needle-biopsy mode (Session > Procedure > Needle biopsy): loads the biopsy
  /// patient (seconds, once), opens the stylus (the Omni emulator over UDP when
  /// options.omni_udp_port is set, else the keyboard), ends and stores the running
  /// cholecystectomy and releases its arms (zero force first), then shows the needle window. On
  /// failure the open window goes on and last_error() says why.
  bool OpenNeedleBiopsy();

  /// The trainer is quitting (after the event loop ended: Quit, SIGTERM): the running session is
  /// stored as unfinished (TrainerWindow::StoreUnfinishedSession).
  void Shutdown();

  /// The window of the open scenario; null until one opened and while the needle mode is open.
  TrainerWindow* window() const { return window_.get(); }
  /// The needle-biopsy window; null unless the needle mode is open.
  needle_mode::NeedleWindow* needle_window() const { return needle_window_.get(); }
  const std::string& last_error() const { return last_error_; }

 private:
  void StorePendingSessionsAtStart();

  TrainerOptions options_;
  QSize window_size_;
  void ConnectOpeners(TrainerWindow& window);

  std::unique_ptr<TrainerWindow> window_;
  std::unique_ptr<needle_mode::NeedleWindow> needle_window_;
  std::shared_ptr<const biopsy::BiopsyPatient> biopsy_patient_;  // loaded once, on the first switch
  std::vector<patient::OrganSurface> biopsy_surfaces_;
  std::filesystem::path scenario_path_;  // the cholecystectomy to go back to
  std::string last_error_;
  bool pending_checked_ = false;  // the pending file is stored once, when the first window opens
  QObject deferred_;  // context of the deferred Open calls: they die with this object
};

}  // namespace vesica::app
