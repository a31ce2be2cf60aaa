#pragma once
// The trainer's main window: the laparoscope view in a QVTKOpenGLNativeWidget with a status line.

#include <QMainWindow>
#include <memory>
#include <vector>

#include "app/render/laparoscope_view.h"

class QVTKOpenGLNativeWidget;

namespace vesica::app {

class TrainerWindow : public QMainWindow {
 public:
  TrainerWindow(const Scenario& scenario, std::unique_ptr<LaparoscopeView> view);
  ~TrainerWindow() override;

 protected:
  /// Instrument keys (keyboard_control.h) reach us before VTK's camera interactor sees them.
  bool eventFilter(QObject* watched, QEvent* event) override;

 private:
  std::unique_ptr<LaparoscopeView> view_;
  QVTKOpenGLNativeWidget* vtk_widget_ = nullptr;
  std::vector<double> max_insertion_m_;
  bool pedal_ = false;
};

}  // namespace vesica::app
