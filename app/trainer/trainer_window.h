#pragma once
// The trainer's main window: the laparoscope view (QVTKOpenGLNativeWidget) of a running
// dissection session, a diagnostics overlay (loop rates and jitter, forces), keyboard control of
// both instruments, pause/reset/end, camera zoom and look-around, and at the end the metrics
// panel; the finished session is stored in the records database with its input recording. With
// Calot's triangle in the scenario the debrief screen opens beside the metrics when the case ends
// (the critical error ends it, as Enter does).
// The window only reads snapshots: it never blocks the physics or haptic loops (SessionRunner).

#include <QMainWindow>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "app/render/laparoscope_view.h"
#include "app/session/live_input.h"
#include "app/session/session_runner.h"
#include "app/session/tool_exchange.h"
#include "app/trainer/session_saver.h"

class QAction;
class QLabel;
class QTimer;
class QVTKOpenGLNativeWidget;

namespace vesica::app {

class ArmBridge;
class MetricsPanel;
namespace calot {
class DebriefScreen;
}

struct TrainerOptions {
  std::string trainee_id = "trainee";
  std::string records_location;          ///< SessionStore location; empty: don't store
  std::filesystem::path recordings_dir;  ///< where session inputs are saved; empty: not saved
  std::filesystem::path replay_file;     ///< drive the instruments from this recording
  bool real_time = true;                 ///< false: replay as fast as the physics goes (tests)
  std::string station = "vesica";
  /// Emulated arms (vesica-armsim over UDP): node n listens on this + 2(n-1) (ArmBridgeOptions).
  int arms_udp_base_port = 20000;
  SaverOptions saver;                    ///< retries of a locked or unreachable database
  /// The needle mode's stylus: the Omni emulator (vesica-omnisim --port P) sends poses to P + 1
  /// and takes forces on P; 0: the keyboard and mouse drive the needle.
  int omni_udp_port = 0;
  std::filesystem::path patient_dir;     ///< the biopsy patient's files; empty: data/patients
  /// Needle mode: a registration result (vesica-register's mesh and displacement.csv) moves the
  /// liver instead of ChainMail when both are given.
  std::filesystem::path liver_motion_mesh, liver_motion;
};

class TrainerWindow : public QMainWindow {
 public:
  /// Builds the session (model already built) and starts its loops.
  TrainerWindow(const Scenario& scenario, std::unique_ptr<LaparoscopeView> view,
                std::shared_ptr<const physics::DissectionModel> model, const TrainerOptions& options);
  ~TrainerWindow() override;

  enum class InputChoice { kKeyboard, kReplay, kArms };
  /// Starts a new session driven by `choice` (a replay needs its file). On failure (a broken
  /// recording, an arm transport that cannot open) the running session goes on, or the keyboard
  /// takes over when there is none; last_error() says why. Returns false on failure.
  bool StartSession(InputChoice choice, const std::filesystem::path& replay_file);

  /// Ends the session now (as the End key does).
  void EndSession();
  /// The right hand's port takes its next instrument (T, Session > Exchange; with the keyboard
  /// only: the arms' handle button does it for them) and the status line names it.
  void ExchangeRightTool();
  /// What the right hand's port holds now (the keyboard's exchange).
  physics::InstrumentTool right_tool() const { return right_port_.current(); }
  /// Ends the session and stores it before returning (when the window is about to go: another
  /// scenario was opened). Nothing to do when the session has already finished.
  void EndAndStoreSession();
  /// The trainer is quitting (Quit, closing the window, SIGTERM): a session still running is
  /// ended and stored as unfinished when anything happened in it (an instrument moved, the
  /// pedal was pressed); then every queued save is finished (or kept pending) before returning.
  void StoreUnfinishedSession();
  /// True while a finished session is being stored (the status bar shows "saving...").
  bool saving() const;
  /// Starts the session over from the rest state (as the R key does): tissue and instruments
  /// (keyboard and mouse poses, pedal) back where the scenario puts them; the finished one, if
  /// it was, stays stored and the new one is stored when it ends.
  void ResetSession();
  /// Session > Open scenario... asks for a scenario file and calls `open` with it (TrainerApp
  /// replaces this window). Without an opener the action is disabled.
  void SetScenarioOpener(std::function<void(const std::filesystem::path&)> open);
  /// What Session > Open scenario... does once the file is chosen: hands it to the opener.
  /// Returns false without an opener.
  bool RequestScenario(const std::filesystem::path& scenario_path);
  /// Session > Procedure > Needle biopsy calls `open` (TrainerApp ends and stores this session,
  /// releases the arms, and opens the needle mode). Without an opener the action is disabled.
  void SetNeedleBiopsyOpener(std::function<void()> open);
  /// What the menu item does: hands over to the opener. False without one.
  bool RequestNeedleBiopsy();
  /// Shows an error in the status bar and keeps it as last_error().
  void ShowError(const std::string& message);
  const Scenario& scenario() const { return scenario_; }
  bool session_finished() const { return stored_ || finished_shown_; }
  /// Id of the stored record, once the finished session was written.
  std::optional<std::int64_t> stored_session_id() const { return stored_id_; }
  MetricsPanel* metrics_panel() const { return metrics_panel_; }
  /// The Calot step's debrief (in the dock "calot_debrief_dock", shown when a case with the step
  /// ends); nullptr when the scenario has no [calot_triangle].
  calot::DebriefScreen* calot_debrief() const { return calot_debrief_; }
  QLabel* diagnostics() const { return diagnostics_; }
  /// The three loops' rates and jitter so far, one line each (the overlay's text; logged at exit
  /// so that a run under Xvfb states the software-rendering rate).
  std::string LoopRatesSummary() const;
  /// The haptic arms' state, one line per arm ("left arm: ok"), as the surgeon's view shows it;
  /// empty when no arm is connected.
  std::string ArmStatusLines() const;
  /// The last error shown (records not writable, physics stopped); empty if none.
  const std::string& last_error() const { return last_error_; }

 protected:
  bool eventFilter(QObject* watched, QEvent* event) override;
  void closeEvent(QCloseEvent* event) override;

 private:
  void Tick();  // render timer: snapshot -> view, overlay, end-of-session handling
  RunnerStatus EndAndWait();
  std::unique_ptr<ArmBridge> OpenArms() const;  // the scenario's arms; throws why they cannot open  // ends the session, waits (bounded) for physics to stop
  void OnFinished(const RunnerStatus& status, bool unfinished = false);
  void HideEndOfSessionDocks();  // the metrics and the debrief: a new session starts
  void TakeSaveResults();  // the saver's news -> stored_id_, status bar
  void OpenHistory();
  void OpenCalibration();  // Tools > Calibrate arms: the arms released to the panel while it is open

  Scenario scenario_;
  TrainerOptions options_;
  std::unique_ptr<LaparoscopeView> view_;
  std::shared_ptr<const physics::DissectionModel> model_;
  std::shared_ptr<LiveInput> live_input_;  // null unless the keyboard drives
  std::unique_ptr<ArmBridge> arms_;        // declared before runner_: its threads use the arms
  std::unique_ptr<SessionRunner> runner_;
  QVTKOpenGLNativeWidget* vtk_widget_ = nullptr;
  QLabel* diagnostics_ = nullptr;
  QLabel* saving_label_ = nullptr;  // "saving..." while the saver works
  QLabel* lag_label_ = nullptr;     // "physics behind real time" while it is
  MetricsPanel* metrics_panel_ = nullptr;
  calot::DebriefScreen* calot_debrief_ = nullptr;  // null without a triangle
  QTimer* timer_ = nullptr;
  LoopStats render_stats_;
  void SendManualPoses();          // keyboard/mouse poses and pedal -> the live input
  bool MouseEvent(QEvent* event);  // a drag or wheel that moves an instrument; true if used

  std::vector<physics::InstrumentPose> poses_, initial_poses_;
  InputChoice input_choice_ = InputChoice::kKeyboard;
  std::unique_ptr<SessionSaver> saver_;  // null when sessions are not stored
  std::uint64_t save_ticket_ = 0;        // the saver's ticket of this window's latest session
  std::string recording_note_;           // why the last session's input was not saved, if it was not
  int drag_instrument_ = -1;  // instrument a mouse button is dragging, -1: none
  int drag_x_ = 0, drag_y_ = 0;
  std::vector<double> max_insertion_m_;
  bool pedal_ = false;
  ToolExchange right_port_;  // the keyboard's exchange (T); the arms' handle button has its own
  bool finished_shown_ = false, stored_ = false;
  std::optional<std::int64_t> stored_id_;
  int session_number_ = 0;  // RunnerStatus::session of the session this window shows
  std::function<void(const std::filesystem::path&)> open_scenario_;
  QAction* open_scenario_action_ = nullptr;
  std::function<void()> open_needle_biopsy_;
  QAction* needle_biopsy_action_ = nullptr;
  std::string last_error_;
  std::int64_t started_unix_s_ = 0;
};

}  // namespace vesica::app
