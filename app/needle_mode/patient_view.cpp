#include "app/needle_mode/patient_view.h"

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkCellArray.h>
#include <vtkLight.h>
#include <vtkLineSource.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkPolyDataNormals.h>
#include <vtkProperty.h>
#include <vtkRenderer.h>
#include <vtkTubeFilter.h>

#include <array>
#include <string>

namespace vesica::app::needle_mode {
namespace {

enum class Motion { kStill, kLiver, kDiaphragm, kRib, kTumour };

struct Look {
  std::array<double, 3> colour;
  double opacity;
  double specular;
};

Look LookOf(const std::string& organ) {
  if (organ == "skin") return {{0.93, 0.76, 0.66}, 0.18, 0.1};
  if (organ == "lungs") return {{0.93, 0.62, 0.62}, 0.25, 0.2};
  if (organ == "diaphragm") return {{0.72, 0.30, 0.28}, 0.55, 0.2};
  if (organ == "liver") return {{0.50, 0.14, 0.09}, 1.0, 0.35};
  if (organ == "tumour") return {{0.96, 0.86, 0.32}, 1.0, 0.3};
  if (organ == "gallbladder") return {{0.32, 0.50, 0.22}, 1.0, 0.4};
  if (organ == "colon") return {{0.78, 0.58, 0.48}, 1.0, 0.2};
  return {{0.95, 0.92, 0.82}, 1.0, 0.2};  // spine, sternum, ribs and their cartilage: bone
}

}  // namespace

struct PatientView::Organ {
  std::string name;
  Motion motion = Motion::kStill;
  int rib = -1;  // index into the model's ribs
  std::vector<Eigen::Vector3d> rest;
  physics::LatticeEmbedding embedding;
  vtkSmartPointer<vtkPoints> points;
  vtkSmartPointer<vtkPolyData> polydata;
  vtkSmartPointer<vtkPolyDataNormals> normals;
  vtkSmartPointer<vtkActor> actor;
};

patient::MeshingOptions DisplayMeshing() {
  patient::MeshingOptions options;
  options.decimate_fraction = 0.95;
  return options;
}

PatientView::PatientView(const biopsy::BiopsyPatient& patient, std::vector<patient::OrganSurface> surfaces)
    : patient_(patient), renderer_(vtkSmartPointer<vtkRenderer>::New()) {
  renderer_->SetBackground(0.08, 0.09, 0.11);
  const physics::BreathingPatientModel& model = *patient.model;
  for (patient::OrganSurface& surface : surfaces) {
    auto organ = std::make_unique<Organ>();
    organ->name = surface.organ;
    const physics::TriangleMesh& mesh = surface.mesh;
    for (int v = 0; v < mesh.num_vertices(); ++v) organ->rest.push_back(mesh.vertices.row(v).transpose());
    if (organ->name == "liver") {
      organ->motion = Motion::kLiver;
      organ->embedding = physics::EmbedPoints(model.liver.lattice, model.volume, organ->rest);
    } else if (organ->name == "diaphragm") {
      organ->motion = Motion::kDiaphragm;
      organ->embedding = physics::EmbedPoints(model.diaphragm.lattice, model.volume, organ->rest);
    } else if (organ->name == "tumour") {
      organ->motion = Motion::kTumour;
    } else if (organ->name.starts_with("rib_")) {
      const bool left = organ->name[4] == 'l';
      const int number = std::stoi(organ->name.substr(5));
      for (std::size_t r = 0; r < model.ribs.size(); ++r)
        if (model.ribs[r].left == left && model.ribs[r].number == number) organ->rib = static_cast<int>(r);
      if (organ->rib >= 0) organ->motion = Motion::kRib;
    }
    organ->points = vtkSmartPointer<vtkPoints>::New();
    organ->points->SetDataTypeToDouble();
    for (const Eigen::Vector3d& p : organ->rest) organ->points->InsertNextPoint(p.x(), p.y(), p.z());
    auto triangles = vtkSmartPointer<vtkCellArray>::New();
    for (int t = 0; t < mesh.num_triangles(); ++t) {
      const vtkIdType ids[3] = {mesh.triangles(t, 0), mesh.triangles(t, 1), mesh.triangles(t, 2)};
      triangles->InsertNextCell(3, ids);
    }
    organ->polydata = vtkSmartPointer<vtkPolyData>::New();
    organ->polydata->SetPoints(organ->points);
    organ->polydata->SetPolys(triangles);
    organ->normals = vtkSmartPointer<vtkPolyDataNormals>::New();
    organ->normals->SetInputData(organ->polydata);
    organ->normals->SplittingOff();
    auto mapper = vtkSmartPointer<vtkPolyDataMapper>::New();
    mapper->SetInputConnection(organ->normals->GetOutputPort());
    organ->actor = vtkSmartPointer<vtkActor>::New();
    organ->actor->SetMapper(mapper);
    const Look look = LookOf(organ->name);
    vtkProperty* property = organ->actor->GetProperty();
    property->SetColor(look.colour[0], look.colour[1], look.colour[2]);
    property->SetOpacity(look.opacity);
    property->SetSpecular(look.specular);
    property->SetSpecularPower(30);
    if (look.opacity < 1.0) property->BackfaceCullingOn();
    renderer_->AddActor(organ->actor);
    if (organ->motion == Motion::kTumour) tumour_ = organ.get();
    organs_.push_back(std::move(organ));
  }
  needle_line_ = vtkSmartPointer<vtkLineSource>::New();
  auto tube = vtkSmartPointer<vtkTubeFilter>::New();
  tube->SetInputConnection(needle_line_->GetOutputPort());
  tube->SetRadius(0.0008);  // an 18 G biopsy needle is 1.2 mm across; drawn a little thicker
  tube->SetNumberOfSides(10);
  auto needle_mapper = vtkSmartPointer<vtkPolyDataMapper>::New();
  needle_mapper->SetInputConnection(tube->GetOutputPort());
  needle_actor_ = vtkSmartPointer<vtkActor>::New();
  needle_actor_->SetMapper(needle_mapper);
  needle_actor_->GetProperty()->SetColor(0.82, 0.84, 0.88);
  needle_actor_->GetProperty()->SetSpecular(0.8);
  needle_actor_->GetProperty()->SetSpecularPower(60);
  renderer_->AddActor(needle_actor_);
  renderer_->SetUseDepthPeeling(false);
  renderer_->SetMaximumNumberOfPeels(4);
  ResetCamera();
}

PatientView::~PatientView() = default;

vtkRenderer* PatientView::renderer() const { return renderer_; }

void PatientView::ResetCamera() {
  const Eigen::Vector3d target = patient_.model->liver.tumour_centre_m;
  vtkCamera* camera = renderer_->GetActiveCamera();
  camera->SetFocalPoint(target.x(), target.y(), target.z());
  // From the patient's right (-x), anterior (+y) and a little cranial, 85 cm away.
  const Eigen::Vector3d eye = target + 0.85 * Eigen::Vector3d(-0.55, 0.75, 0.35).normalized();
  camera->SetPosition(eye.x(), eye.y(), eye.z());
  camera->SetViewUp(0, 0, 1);
  camera->SetViewAngle(30);
  renderer_->ResetCameraClippingRange();
}

void PatientView::SetTumourVisible(bool visible) {
  if (tumour_) tumour_->actor->SetVisibility(visible);
}

bool PatientView::tumour_visible() const { return tumour_ && tumour_->actor->GetVisibility(); }

void PatientView::Update(const physics::PatientSnapshot& snapshot, const biopsy::NeedleFrame& needle) {
  const physics::BreathingPatientModel& model = *patient_.model;
  std::vector<Eigen::Vector3d> u;
  const auto displacements = [&](const physics::BlockLattice& lattice, const std::vector<Eigen::Vector3d>& now) {
    u.resize(now.size());
    for (std::size_t e = 0; e < now.size() && e < lattice.rest_m.size(); ++e) u[e] = now[e] - lattice.rest_m[e];
  };
  for (auto& organ : organs_) {
    if (organ->motion == Motion::kStill) continue;
    if (organ->motion == Motion::kLiver) displacements(model.liver.lattice, snapshot.liver_m);
    if (organ->motion == Motion::kDiaphragm) displacements(model.diaphragm.lattice, snapshot.diaphragm_m);
    const Eigen::Vector3d tumour_shift = snapshot.tumour_centre_m - model.liver.tumour_centre_m;
    for (std::size_t v = 0; v < organ->rest.size(); ++v) {
      Eigen::Vector3d p = organ->rest[v];
      switch (organ->motion) {
        case Motion::kLiver:
        case Motion::kDiaphragm:
          if (!u.empty()) p += organ->embedding.Displacement(v, u);
          break;
        case Motion::kTumour:
          p += tumour_shift;
          break;
        case Motion::kRib:
          if (organ->rib < static_cast<int>(snapshot.ribs.size())) p = snapshot.ribs[organ->rib].Apply(p);
          break;
        case Motion::kStill:
          break;
      }
      organ->points->SetPoint(static_cast<vtkIdType>(v), p.x(), p.y(), p.z());
    }
    organ->points->Modified();
  }
  const Eigen::Vector3d tip = needle.pose.tip_m;
  const Eigen::Vector3d hub = tip - 0.15 * needle.pose.direction.normalized();  // a 15 cm needle
  needle_line_->SetPoint1(hub.x(), hub.y(), hub.z());
  needle_line_->SetPoint2(tip.x(), tip.y(), tip.z());
  needle_line_->Modified();
}

}  // namespace vesica::app::needle_mode
