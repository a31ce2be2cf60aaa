#pragma once
// The 3D view of the biopsy patient (VTK): the organ surfaces of MeshPatient, moving with the
// breathing (liver and diaphragm with their ChainMail lattices, ribs with their poses, the tumour
// with the liver), the skin translucent so the ribs and the liver show through, and the needle.
// The tumour can be hidden (a trainee should find it on the CT, not in the 3D view).

#include <vtkSmartPointer.h>

#include <memory>
#include <vector>

#include "app/biopsy/biopsy_patient.h"
#include "app/biopsy/biopsy_runner.h"
#include "app/patient/patient_meshing.h"

class vtkActor;
class vtkLineSource;
class vtkPoints;
class vtkPolyData;
class vtkRenderer;

namespace vesica::app::needle_mode {

/// How the needle mode meshes the patient for display: decimated further than MeshPatient's
/// default (a 2 mm CT's surfaces are ~420k triangles, which software rendering draws at 5 Hz).
patient::MeshingOptions DisplayMeshing();

class PatientView {
 public:
  /// `surfaces`: MeshPatient of the patient's label map.
  PatientView(const biopsy::BiopsyPatient& patient, std::vector<patient::OrganSurface> surfaces);
  ~PatientView();
  PatientView(const PatientView&) = delete;
  PatientView& operator=(const PatientView&) = delete;

  vtkRenderer* renderer() const;
  /// Moves the organs to the snapshot and the needle to the frame.
  void Update(const physics::PatientSnapshot& patient, const biopsy::NeedleFrame& needle);
  void SetTumourVisible(bool visible);
  [[nodiscard]] bool tumour_visible() const;
  /// The camera looking from the patient's right, anterior and a little cranial onto the tumour
  /// (where the trainee stands).
  void ResetCamera();

 private:
  struct Organ;
  const biopsy::BiopsyPatient& patient_;
  std::vector<std::unique_ptr<Organ>> organs_;
  vtkSmartPointer<vtkRenderer> renderer_;
  vtkSmartPointer<vtkLineSource> needle_line_;
  vtkSmartPointer<vtkActor> needle_actor_;
  Organ* tumour_ = nullptr;
};

}  // namespace vesica::app::needle_mode
