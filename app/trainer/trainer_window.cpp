#include "app/trainer/trainer_window.h"

#include <QStatusBar>
#include <QVTKOpenGLNativeWidget.h>
#include <vtkGenericOpenGLRenderWindow.h>
#include <vtkRenderer.h>

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
  statusBar()->showMessage(QString::fromStdString(scenario.description));
  resize(1280, 720);
}

TrainerWindow::~TrainerWindow() = default;

}  // namespace vesica::app
