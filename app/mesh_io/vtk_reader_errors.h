#pragma once
// VTK readers report malformed content through error events on the reader and its executive,
// and through VTK's output window for their helpers (an XML reader's parser), and otherwise return
// a truncated mesh. VtkReaderErrors collects the first of these, the root cause, while a reader
// runs, so that a file is refused in VTK's own words:
//   "liver.vtk: cannot be read: Unrecognized keyword: nan"

#include <vtkSmartPointer.h>

#include <filesystem>
#include <string>

class vtkAlgorithm;
class vtkCallbackCommand;

namespace vesica::app {

class CapturingOutputWindow;

/// Observes `reader` from construction to destruction. The output window is VTK's global: it is
/// replaced meanwhile and restored after (mesh files are read on one thread at a time).
class VtkReaderErrors {
 public:
  explicit VtkReaderErrors(vtkAlgorithm* reader);
  ~VtkReaderErrors();
  VtkReaderErrors(const VtkReaderErrors&) = delete;
  VtkReaderErrors& operator=(const VtkReaderErrors&) = delete;

  /// Throws physics::MeshError "PATH: cannot be read: REASON" when VTK reported an error.
  void ThrowIfAny(const std::filesystem::path& path) const;

 private:
  vtkSmartPointer<vtkCallbackCommand> callback_;
  vtkSmartPointer<CapturingOutputWindow> window_;
  std::string message_;
};

}  // namespace vesica::app
