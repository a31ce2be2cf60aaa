#include "app/trainer/trainer_window.h"

#include <QKeyEvent>
#include <QStatusBar>
#include <QVTKOpenGLNativeWidget.h>
#include <vtkGenericOpenGLRenderWindow.h>
#include <vtkRenderer.h>

#include "app/trainer/keyboard_control.h"

namespace vesica::app {

TrainerWindow::TrainerWindow(const Scenario& scenario, std::unique_ptr<LaparoscopeView> view)
    : view_(std::move(view)) {
  setWindowTitle(QString::fromStdString("Vesica — " + scenario.name));
  vtk_widget_ = new QVTKOpenGLNativeWidget(this);
  auto window = vtkSmartPointer<vtkGenericOpenGLRenderWindow>::New();
  window->SetMultiSamples(0);  // keeps translucent membranes and smoke visible on Mesa
  window->AddRenderer(view_->renderer());
  vtk_widget_->setRenderWindow(window);
  setCentralWidget(vtk_widget_);
  for (const auto& instrument : scenario.instruments) max_insertion_m_.push_back(instrument.shaft_length_m);
  vtk_widget_->installEventFilter(this);
  vtk_widget_->setFocus();
  statusBar()->showMessage(QString::fromStdString(KeyboardHelp()));
  setToolTip(QString::fromStdString(scenario.description));
  resize(1280, 720);
}

bool TrainerWindow::eventFilter(QObject* watched, QEvent* event) {
  if (watched == vtk_widget_ && event->type() == QEvent::KeyPress) {
    const QString text = static_cast<QKeyEvent*>(event)->text();
    if (text.size() == 1) {
      auto poses = view_->poses();
      if (ApplyInstrumentKey(text.at(0).toLatin1(), poses, max_insertion_m_, pedal_)) {
        for (std::size_t i = 0; i < poses.size(); ++i) view_->SetInstrumentPose(i, poses[i]);
        vtk_widget_->renderWindow()->Render();
        return true;
      }
    }
  }
  return QMainWindow::eventFilter(watched, event);
}

TrainerWindow::~TrainerWindow() = default;

}  // namespace vesica::app
