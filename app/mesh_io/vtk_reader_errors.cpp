#include "app/mesh_io/vtk_reader_errors.h"

#include <vtkAlgorithm.h>
#include <vtkCallbackCommand.h>
#include <vtkCommand.h>
#include <vtkExecutive.h>
#include <vtkObjectFactory.h>
#include <vtkOutputWindow.h>

#include <algorithm>
#include <cctype>

#include "physics/mesh/mesh_validation.h"

namespace vesica::app {

namespace {

/// VTK's error text is "ERROR: In SOURCE.cxx, line N\nvtkClass (0x...): REASON\n\n" (a generic
/// warning's "Generic Warning: In SOURCE.cxx, line N\nREASON\n\n"): the REASON.
std::string VtkReason(std::string text) {
  if (text.rfind("ERROR: In ", 0) == 0 || text.rfind("Generic Warning: In ", 0) == 0)
    if (const auto nl = text.find('\n'); nl != std::string::npos) text.erase(0, nl + 1);
  if (const auto at = text.find("): "); at != std::string::npos && text.rfind("vtk", 0) == 0) text.erase(0, at + 3);
  std::replace(text.begin(), text.end(), '\n', ' ');
  while (!text.empty() && std::isspace(static_cast<unsigned char>(text.back()))) text.pop_back();
  return text;
}

}  // namespace

/// While installed, VTK's error texts from objects nobody observes go to `error`, and its generic
/// warnings (what the legacy reader says of data it cannot parse, before it returns garbage) to
/// `warning`, instead of stderr; other texts pass on to the previous window.
class CapturingOutputWindow : public vtkOutputWindow {
 public:
  static CapturingOutputWindow* New();
  vtkTypeMacro(CapturingOutputWindow, vtkOutputWindow)

      void DisplayErrorText(const char* text) override {
    if (error && error->empty() && text) *error = VtkReason(text);
  }
  void DisplayText(const char* text) override {
    if (previous) previous->DisplayText(text);
  }
  void DisplayWarningText(const char* text) override {
    if (previous) previous->DisplayWarningText(text);
  }
  void DisplayGenericWarningText(const char* text) override {
    if (warning && warning->empty() && text) *warning = VtkReason(text);
  }
  void DisplayDebugText(const char* text) override {
    if (previous) previous->DisplayDebugText(text);
  }

  std::string* error = nullptr;
  std::string* warning = nullptr;
  vtkSmartPointer<vtkOutputWindow> previous;
};
vtkStandardNewMacro(CapturingOutputWindow);

VtkReaderErrors::VtkReaderErrors(vtkAlgorithm* reader)
    : callback_(vtkSmartPointer<vtkCallbackCommand>::New()), window_(vtkSmartPointer<CapturingOutputWindow>::New()) {
  callback_->SetClientData(&message_);
  callback_->SetCallback([](vtkObject*, unsigned long, void* client, void* call) {
    auto* message = static_cast<std::string*>(client);
    if (message->empty() && call) *message = VtkReason(static_cast<const char*>(call));
  });
  reader->AddObserver(vtkCommand::ErrorEvent, callback_);
  reader->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, callback_);
  window_->previous = vtkOutputWindow::GetInstance();
  window_->error = &message_;
  window_->warning = &warning_;
  vtkOutputWindow::SetInstance(window_);
}

VtkReaderErrors::~VtkReaderErrors() { vtkOutputWindow::SetInstance(window_->previous); }

void VtkReaderErrors::ThrowIfAny(const std::filesystem::path& path) const {
  if (message_.empty() && warning_.empty()) return;
  // The warning, when there is one, came first: the cause of the error that followed.
  const std::string reason =
      warning_.empty() ? message_ : message_.empty() ? warning_ : warning_ + " (then: " + message_ + ")";
  throw physics::MeshError(path.string() + ": cannot be read: " + reason);
}

}  // namespace vesica::app
