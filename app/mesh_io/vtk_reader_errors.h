#pragma once
// VTK readers report malformed content through error events on the reader and its executive,
// through VTK's output window for their helpers (an XML reader's parser) and as generic warnings
// (the legacy reader on data it cannot parse, after which it returns garbage). VtkReaderErrors
// collects the first of each while a reader runs, so that a file is refused in VTK's own words:
//   "liver.vtk: cannot be read: Error reading ascii data. Possible mismatch of datasize with
//    declaration. (then: Unrecognized keyword: nan)"

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

  /// Throws physics::MeshError "PATH: cannot be read: REASON" when VTK reported an error or a
  /// generic warning.
  void ThrowIfAny(const std::filesystem::path& path) const;

 private:
  vtkSmartPointer<vtkCallbackCommand> callback_;
  vtkSmartPointer<CapturingOutputWindow> window_;
  std::string message_;  ///< the first error
  std::string warning_;  ///< the first generic warning
};

}  // namespace vesica::app
