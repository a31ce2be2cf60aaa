#pragma once
// The trainer's main window: the laparoscope view in a QVTKOpenGLNativeWidget with a status line.

#include <QMainWindow>
#include <memory>

#include "app/render/laparoscope_view.h"

class QVTKOpenGLNativeWidget;

namespace vesica::app {

class TrainerWindow : public QMainWindow {
 public:
  TrainerWindow(const Scenario& scenario, std::unique_ptr<LaparoscopeView> view);
  ~TrainerWindow() override;

 private:
  std::unique_ptr<LaparoscopeView> view_;
  QVTKOpenGLNativeWidget* vtk_widget_ = nullptr;
};

}  // namespace vesica::app
