#pragma once
// The trainer's needle-biopsy mode (issue 34): the breathing patient in 3D with the needle, the
// CT guidance images through the needle (axial and the needle's oblique plane) resliced as the
// patient breathes, the breathing panel, and at the end the biopsy's metrics, stored in the
// records next to the cholecystectomies. The needle is a stylus: the Omni emulator over UDP (or an
// Omni), or the keyboard and mouse. The window only reads the haptic thread's snapshots.

#include <QMainWindow>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "app/biopsy/biopsy_runner.h"
#include "app/patient/patient_meshing.h"
#include "app/trainer/session_saver.h"

class QCheckBox;
class QLabel;
class QTimer;
class QVTKOpenGLNativeWidget;

namespace vesica::app {
class MetricsPanel;
}

namespace vesica::app::needle_mode {

class BreathingPanel;
class CtSliceWidget;
class PatientView;

struct NeedleModeOptions {
  std::string trainee_id = "trainee";
  std::string station = "vesica";
  std::string records_location;          ///< SessionStore location; empty: not stored
  std::filesystem::path recordings_dir;  ///< where each biopsy's stylus stream is saved; empty: not saved
  SaverOptions saver;
  double slice_period_s = 0.1;                          ///< the CT images are resliced this often (10 Hz)
  physics::BreathingPatient::LiverMotion liver_motion;  ///< a registered breathing (issue 35); empty: ChainMail
};

class NeedleWindow : public QMainWindow {
 public:
  /// `stylus` must be open; `servo` runs once a haptic tick before it is read (a UDP stylus' Tick).
  NeedleWindow(std::shared_ptr<const biopsy::BiopsyPatient> patient, std::vector<patient::OrganSurface> surfaces,
               std::shared_ptr<device::StylusDevice> stylus, std::function<void()> servo,
               const NeedleModeOptions& options);
  ~NeedleWindow() override;

  /// Session > Procedure > Laparoscopic cholecystectomy: `switch_back` is called (deferred) once the
  /// biopsy session is ended and stored.
  void SetProcedureSwitcher(std::function<void()> switch_back);
  /// Ends the running session (stored as unfinished when the needle moved) and waits until it is
  /// stored or kept pending. Before the window goes (a procedure switch, quitting).
  void EndAndStoreSession();
  /// Starts a new biopsy (R).
  void ResetSession();

  // For tests and scripts.
  PatientView& patient_view() { return *view_; }
  CtSliceWidget* axial_slice() const { return axial_; }
  CtSliceWidget* oblique_slice() const { return oblique_; }
  BreathingPanel* breathing_panel() const { return breathing_; }
  MetricsPanel* metrics_panel() const { return metrics_; }
  QLabel* device_label() const { return device_label_; }
  biopsy::BiopsyRunner& runner() { return *runner_; }
  bool finished_shown() const { return finished_shown_; }
  std::optional<std::int64_t> stored_session_id() const { return stored_id_; }
  const std::string& last_error() const { return last_error_; }
  /// One GUI update now (the timer's work): snapshot -> 3D view, CT images when due, status.
  void Tick();

 protected:
  bool eventFilter(QObject* watched, QEvent* event) override;
  void closeEvent(QCloseEvent* event) override;

 private:
  void StartRunner();
  void Finish(bool unfinished);
  void UpdateSlices(const physics::PatientSnapshot& patient, const biopsy::NeedleFrame& needle);
  void TakeSaveResults();

  std::shared_ptr<const biopsy::BiopsyPatient> patient_;
  std::shared_ptr<device::StylusDevice> stylus_;
  std::function<void()> servo_;
  NeedleModeOptions options_;
  std::unique_ptr<biopsy::BiopsyRunner> runner_;
  std::unique_ptr<PatientView> view_;
  physics::DeformedCt slice_ct_;  // the GUI's own view of the CT through the breathing
  QVTKOpenGLNativeWidget* vtk_widget_ = nullptr;
  CtSliceWidget* axial_ = nullptr;
  CtSliceWidget* oblique_ = nullptr;
  BreathingPanel* breathing_ = nullptr;
  MetricsPanel* metrics_ = nullptr;
  QCheckBox* show_tumour_ = nullptr;
  QLabel* device_label_ = nullptr;
  QLabel* task_label_ = nullptr;
  QTimer* timer_ = nullptr;
  std::unique_ptr<SessionSaver> saver_;
  std::uint64_t save_ticket_ = 0;
  std::function<void()> switch_back_;
  double next_slice_s_ = 0.0;
  bool finished_shown_ = false;
  bool needle_moved_ = false;
  std::optional<std::int64_t> stored_id_;
  std::int64_t started_unix_s_ = 0;
  std::string last_error_;
};

}  // namespace vesica::app::needle_mode
