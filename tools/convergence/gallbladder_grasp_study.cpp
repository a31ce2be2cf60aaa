#include "tools/convergence/gallbladder_grasp_study.h"

#include <Eigen/Geometry>
#include <cmath>
#include <vector>

#include "app/mesh_io/mesh_io.h"
#include "physics/fem/fem_model.h"
#include "physics/fem/linear_statics.h"
#include "physics/mesh/mesh_topology.h"

namespace vesica::convergence {

bool InJaw(const Eigen::Vector3d& p, const ToolLoadReference& ref) {
  const Eigen::Vector3d normal = ref.prescribed_m.normalized();
  const Eigen::Vector3d across = normal.cross(ref.jaw_long_axis);
  const Eigen::Vector3d d = p - ref.centre_m;
  return std::abs(d.dot(ref.jaw_long_axis)) <= 0.5 * kJawLength_m && std::abs(d.dot(across)) <= 0.5 * kJawWidth_m &&
         d.dot(normal) > -0.004;
}

GallbladderGraspResult SolveGallbladderGrasp(const physics::TetrahedralMesh& mesh, const physics::TriangleMesh& liver,
                                             const ToolLoadReference& ref) {
  const physics::TetBoundary boundary = physics::ExtractBoundary(mesh);
  std::vector<physics::DirichletNode> held;
  std::vector<int> jaw;
  for (int s = 0; s < boundary.surface.num_vertices(); ++s) {
    const Eigen::RowVector3d p = boundary.surface.vertices.row(s);
    const double to_liver = (liver.vertices.rowwise() - p).rowwise().norm().minCoeff();
    const int node = boundary.surface_to_volume(s);
    if (to_liver < kBedDistance_m) {
      held.push_back({node});
    } else if (InJaw(p.transpose(), ref)) {
      held.push_back({node});
      jaw.push_back(node);
    }
  }
  physics::FemSettings settings;
  settings.body_name = "gallbladder";
  settings.material = {2300.0, 0.45, 1000.0};  // gallbladder paper, Table 1
  settings.element_model = physics::ElementModel::kLinear;
  const physics::FemModel model = physics::BuildFemModel(mesh, settings, held);
  Eigen::VectorXd prescribed = Eigen::VectorXd::Zero(model.num_dofs());
  for (int node : jaw) prescribed.segment<3>(3 * node) = ref.prescribed_m;
  const Eigen::VectorXd u = physics::SolveLinearStatics(model, Eigen::VectorXd::Zero(model.num_dofs()), prescribed);
  const Eigen::VectorXd reaction = physics::PatternMatrix(model.pattern, model.linear_stiffness_values) * u;

  GallbladderGraspResult r;
  r.nodes = mesh.num_vertices();
  r.jaw_nodes = static_cast<int>(jaw.size());
  for (int node : jaw) r.force_N += reaction.segment<3>(3 * node);
  r.force_error = (r.force_N - ref.force_N).norm() / ref.force_N.norm();
  double edges = 0;
  for (int f = 0; f < boundary.surface.num_triangles(); ++f)
    edges += (boundary.surface.vertices.row(boundary.surface.triangles(f, 0)) -
              boundary.surface.vertices.row(boundary.surface.triangles(f, 1)))
                 .norm();
  r.mean_edge_m = edges / boundary.surface.num_triangles();
  return r;
}

physics::TetrahedralMesh ReadTrainerGallbladder(const std::string& source_dir, int nodes) {
  return app::ReadTetrahedralMesh(source_dir + "/data/anatomy/gallbladder_" + std::to_string(nodes) + ".vtu");
}

ToolLoadReference ReadGallbladderGraspReference(const std::string& source_dir) {
  return ReadToolLoadReference(source_dir + "/tests/fem/data/gallbladder_grasp_reference.txt");
}

}  // namespace vesica::convergence
