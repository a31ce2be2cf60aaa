#pragma once
// Tools > Calibrate arms: the technician's calibration (vesica-calibrate's commands, the same
// library: app/calibrate/commands.h) in a trainer window. It finds the arms on the trainer's own
// transport (scan, info), calibrates a chosen arm (all joints and steps, or one) on a worker
// thread with a progress bar and the time left per step, asks before anything moves, logs the
// notes, stops on Abort (the arm is left disabled with its previous calibration in force), and
// ends with the checks (measured value, tolerance, pass/fail) and the written HTML report.
// The panel holds the bus while it is open: whoever opens it releases the arms first (the
// trainer's session stops driving them) and takes them back when it closes (QDialog::finished).

#include <QDialog>
#include <memory>
#include <string>

namespace vesica::app {

struct Scenario;
namespace calibrate {
struct ToolOptions;
struct CommandOutcome;
class ToolSession;
}  // namespace calibrate

class CalibrationPanel : public QDialog {
 public:
  /// `options`: the bus (BusSpec: SocketCAN, UDP to vesica-armsim, or emulated arms), the data
  /// folder and the date, as vesica-calibrate's command line gives them. Scans at once.
  explicit CalibrationPanel(const calibrate::ToolOptions& options, QWidget* parent = nullptr);
  /// The panel for a trainer: the arms where the trainer drives them (calibration_bus.h), the
  /// tool's default data folder.
  static CalibrationPanel* ForTrainer(const Scenario& scenario, int arms_udp_base_port, QWidget* parent);
  ~CalibrationPanel() override;

  /// What the buttons do (tests call them too). Ignored while a command runs.
  void StartScan();
  void StartInfo();
  void StartCalibrate();
  /// The Abort button: the running command stops at once.
  void Abort();
  /// Closing while a command runs aborts it and waits for it; then the bus is released.
  void done(int result) override;

  bool busy() const;
  /// The last finished command's outcome (exit code, JSON, text).
  const calibrate::CommandOutcome& last_outcome() const;
  /// The last command's session (its bus and emulated arms), kept until the next command; null
  /// while one runs.
  calibrate::ToolSession* last_session();
  /// The report the last calibration wrote (empty if none); what "Open report" opens.
  std::string report_html() const;

 private:
  struct State;
  void Run(const std::string& command, int arm);
  void Finished();
  void ShowProgress(int arm, const std::string& step, double fraction, double eta_s);
  void ShowResults();

  std::unique_ptr<State> s_;
};

}  // namespace vesica::app
