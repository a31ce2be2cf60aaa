#include "physics/scene/dissection_model.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace vesica::physics {

namespace {
void Require(bool ok, const std::string& field, const std::string& rule) {
  if (!ok) throw std::invalid_argument("dissection settings: " + field + " " + rule);
}

void ValidateDissectionSettings(const DissectionSettings& s) {
  Require(std::isfinite(s.time_step_s) && s.time_step_s > 0, "time_step_s", "must be > 0");
  Require(s.gravity_m_per_s2.allFinite(), "gravity_m_per_s2", "must be finite");
  Require(s.springs.stiffness >= 0 && s.springs.damping >= 0, "springs", "stiffness and damping must be >= 0");
  Require(std::isfinite(s.attach_offset_m) && s.attach_offset_m > 0, "attach_offset_m", "must be > 0");
  Require(s.grasp_compliance_m_per_N >= 0, "grasp_compliance_m_per_N", "must be >= 0");
  Require(s.contact_compliance_m_per_N > 0, "contact_compliance_m_per_N", "must be > 0");
  Require(s.max_correction_per_step_m > 0, "max_correction_per_step_m", "must be > 0");
  Require(s.contact_margin_m > 0, "contact_margin_m", "must be > 0");
  Require(s.touch_tolerance_m >= 0, "touch_tolerance_m", "must be >= 0");
  Require(s.grasp_reach_m >= 0, "grasp_reach_m", "must be >= 0");
  Require(s.membrane_touch_radius_m > 0, "membrane_touch_radius_m", "must be > 0");
  Require(s.hook_length_m > 0, "hook_length_m", "must be > 0");
  Require(std::isfinite(s.grasp_jaw_length_m) && s.grasp_jaw_length_m > 0, "grasp_jaw_length_m", "must be > 0");
  Require(std::isfinite(s.grasp_jaw_width_m) && s.grasp_jaw_width_m > 0, "grasp_jaw_width_m", "must be > 0");
  Require(std::isfinite(s.grasp_subgrid_patch_radius_m) && s.grasp_subgrid_patch_radius_m > 0,
          "grasp_subgrid_patch_radius_m", "must be > 0");
  Require(s.grasp_subgrid_adopt_steps >= 0, "grasp_subgrid_adopt_steps", "must be >= 0");
  Require(s.grasp_subgrid_ramp_steps >= 1, "grasp_subgrid_ramp_steps", "must be >= 1");
  Require(s.compliance_refresh_steps >= 1, "compliance_refresh_steps", "must be >= 1");
  Require(s.compliance_adopt_steps >= 0 && s.compliance_adopt_steps < s.compliance_refresh_steps,
          "compliance_adopt_steps", "must be >= 0 and < compliance_refresh_steps");
  Require(std::isfinite(s.obstacle_margin_m) && s.obstacle_margin_m > 0, "obstacle_margin_m", "must be > 0");
  Require(std::isfinite(s.obstacle_max_depth_m) && s.obstacle_max_depth_m > s.max_correction_per_step_m,
          "obstacle_max_depth_m", "must be > max_correction_per_step_m");
  Require(std::isfinite(s.obstacle_compliance_m_per_N) && s.obstacle_compliance_m_per_N > 0,
          "obstacle_compliance_m_per_N", "must be > 0");
  Require(std::isfinite(s.obstacle_friction) && s.obstacle_friction >= 0, "obstacle_friction", "must be >= 0");
  Require(s.obstacle_max_sweeps >= 1, "obstacle_max_sweeps", "must be >= 1");
  Require(s.obstacle_tolerance_m > 0.0 && std::isfinite(s.obstacle_tolerance_m), "obstacle_tolerance_m",
          "must be > 0 and finite");
}

Eigen::Vector3d DirectionTowardBed(const TriangleMesh& liver, const TetrahedralMesh& gallbladder) {
  Eigen::Vector3d bed = Eigen::Vector3d::Zero();
  int count = 0;
  for (int v = 0; v < liver.num_vertices(); ++v)
    if (liver.vertex_labels.size() == liver.num_vertices() && (liver.vertex_labels[v] & kLabelGallbladderBed) != 0) {
      bed += liver.vertices.row(v).transpose();
      ++count;
    }
  if (count == 0) throw std::invalid_argument("liver surface has no gallbladder-bed labelled vertices");
  bed /= count;
  const Eigen::Vector3d centre = gallbladder.vertices.colwise().mean().transpose();
  const Eigen::Vector3d d = bed - centre;
  if (!(d.norm() > 0)) throw std::invalid_argument("gallbladder centroid coincides with the liver bed centroid");
  return d.normalized();
}
}  // namespace

std::shared_ptr<const DissectionModel> BuildDissectionModel(const DissectionModelInputs& in) {
  ValidateDissectionSettings(in.settings);
  CheckStaticObstacles(in.obstacles);
  for (const InstrumentMount& m : in.instruments)
    Require(m.p_RemoteCentre_W.allFinite() && std::abs(m.reference_direction_W.norm() - 1.0) < 1e-9, "instrument mount",
            "needs a finite remote centre and a unit reference direction");
  auto model = std::make_shared<DissectionModel>();
  model->settings = in.settings;
  model->instruments = in.instruments;
  model->liver = std::make_shared<const BemModel>(
      PrecomputeBemModel(in.liver_surface, in.liver_material, in.liver_source, in.liver_bem));
  FemSettings gb = in.gallbladder;
  gb.time_step_s = in.settings.time_step_s;
  model->gallbladder =
      std::make_shared<const FemModel>(BuildFemModel(in.gallbladder_mesh, gb, in.gallbladder_fixed_nodes));
  model->gallbladder_boundary = ExtractBoundary(in.gallbladder_mesh);
  model->retraction = MakeAssistantRetraction(in.gallbladder_mesh, in.settings.assistant_retraction);
  model->toward_liver = DirectionTowardBed(in.liver_surface, in.gallbladder_mesh);
  ConnectiveTissueSettings tissue;
  tissue.toward_liver = model->toward_liver;
  tissue.offset = in.settings.attach_offset_m;
  model->tissue = CreateConnectiveTissue(in.liver_surface, in.gallbladder_mesh, tissue);
  if (model->tissue.springs.empty())
    throw std::invalid_argument(in.gallbladder_source + ": no connective-tissue spring found within " +
                                std::to_string(in.settings.attach_offset_m) + " m of " + in.liver_source);
  model->obstacles = in.obstacles;
  if (in.settings.gallbladder_rests_on_liver) {
    // Cells of 5 mm; reach covers the margin, the depth and 4 mm of the liver's own motion (its
    // surface moves less under the springs and tools; measured 1-2 mm in the committed replay).
    const double reach_m = in.settings.obstacle_max_depth_m + in.settings.obstacle_margin_m + 0.004;
    model->liver_proximity = SurfaceProximityGrid(in.liver_surface, reach_m, 0.005);
  }
  return model;
}

}  // namespace vesica::physics
