#include "tools/convergence/gallbladder_grasp_study.h"

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "app/mesh_io/mesh_io.h"
#include "physics/fem/cholmod_solver.h"
#include "physics/fem/fem_model.h"
#include "physics/fem/jaw_footprint.h"
#include "physics/fem/linear_statics.h"
#include "physics/mesh/mesh_topology.h"

namespace vesica::convergence {

namespace {

// The jaw's outward normal: the pull's direction, the opposite of the press's.
Eigen::Vector3d JawNormal(const ToolLoadReference& ref, JawLoad load) {
  return (load == JawLoad::kPress ? -1.0 : 1.0) * ref.prescribed_m.normalized();
}

// Minimises the elastic energy under C u = g (C: k x 3n, zero on the held dofs): with X = K^-1 C^T,
// the multipliers solve (C X) mu = g, u = X mu, and the jaw's nodal forces on the body are C^T mu.
Eigen::VectorXd SolveWithMultipliers(const physics::FemModel& model, const Eigen::MatrixXd& c,
                                     const Eigen::VectorXd& g) {
  Eigen::VectorXd k = model.linear_stiffness_values;
  for (int s : model.constrained_slots) k[s] = 0.0;
  for (int i : model.fixed_dofs) k[model.pattern.diagonal_slot[i]] = 1.0;
  physics::CholmodSolver cholesky;
  if (!cholesky.Factorize(model.pattern, k))
    throw std::runtime_error("gallbladder study: the held bed leaves the stiffness singular");
  Eigen::MatrixXd x(c.cols(), c.rows());
  for (Eigen::Index r = 0; r < c.rows(); ++r) {
    Eigen::VectorXd column;
    cholesky.Solve(c.row(r).transpose(), column);
    x.col(r) = column;
  }
  const Eigen::VectorXd mu = (c * x).ldlt().solve(g);
  return c.transpose() * mu;
}

}  // namespace

const char* JawModelName(JawModel model) {
  switch (model) {
    case JawModel::kNodesInside:
      return "nodes inside";
    case JawModel::kFootprintMean:
      return "footprint, mean";
    case JawModel::kFootprintMeanAndTilt:
      return "footprint, mean and tilt";
  }
  return "?";
}

bool InJaw(const Eigen::Vector3d& p, const ToolLoadReference& ref, JawLoad load) {
  const Eigen::Vector3d normal = JawNormal(ref, load);
  const Eigen::Vector3d across = normal.cross(ref.jaw_long_axis);
  const Eigen::Vector3d d = p - ref.centre_m;
  return std::abs(d.dot(ref.jaw_long_axis)) <= 0.5 * kJawLength_m && std::abs(d.dot(across)) <= 0.5 * kJawWidth_m &&
         d.dot(normal) > -0.004;
}

GallbladderGraspResult SolveGallbladderGrasp(const physics::TetrahedralMesh& mesh, const physics::TriangleMesh& liver,
                                             const ToolLoadReference& ref, JawModel jaw_model, JawLoad load) {
  const physics::TetBoundary boundary = physics::ExtractBoundary(mesh);
  const Eigen::Vector3d normal = JawNormal(ref, load);
  std::vector<physics::DirichletNode> held;
  std::vector<int> inside;
  for (int s = 0; s < boundary.surface.num_vertices(); ++s) {
    const Eigen::RowVector3d p = boundary.surface.vertices.row(s);
    const double to_liver = (liver.vertices.rowwise() - p).rowwise().norm().minCoeff();
    const int node = boundary.surface_to_volume(s);
    if (to_liver < kBedDistance_m) {
      held.push_back({node});
    } else if (jaw_model == JawModel::kNodesInside && InJaw(p.transpose(), ref, load)) {
      inside.push_back(node);
    }
  }
  physics::FemSettings settings;
  settings.body_name = "gallbladder";
  settings.material = {2300.0, 0.45, 1000.0};  // gallbladder paper, Table 1
  settings.element_model = physics::ElementModel::kLinear;
  const physics::FemModel bed_held = physics::BuildFemModel(mesh, settings, held);
  const int n = bed_held.num_dofs();

  // The constraints C u = g: per jaw node and component (nodes inside), or per traction mode and
  // component over the footprint; a press prescribes the normal component only.
  std::vector<Eigen::VectorXd> rows;
  std::vector<double> targets;
  std::vector<Eigen::Vector3d> directions;
  if (load == JawLoad::kPress) {
    directions = {normal};
  } else {
    directions = {Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(), Eigen::Vector3d::UnitZ()};
  }
  GallbladderGraspResult r;
  if (jaw_model == JawModel::kNodesInside) {
    for (int node : inside)
      for (const Eigen::Vector3d& dir : directions) {
        Eigen::VectorXd row = Eigen::VectorXd::Zero(n);
        row.segment<3>(3 * node) = dir;
        rows.push_back(row);
        targets.push_back(dir.dot(ref.prescribed_m));
      }
    r.jaw_nodes = static_cast<int>(inside.size());
  } else {
    physics::RectangularFootprint jaw;
    jaw.centre_m = ref.centre_m;
    jaw.normal = normal;
    jaw.long_axis = (ref.jaw_long_axis - ref.jaw_long_axis.dot(normal) * normal).normalized();
    jaw.length_m = kJawLength_m;
    jaw.width_m = kJawWidth_m;
    const physics::FootprintWeights w = physics::ComputeFootprintWeights(boundary, jaw);
    const int modes = jaw_model == JawModel::kFootprintMeanAndTilt ? 3 : 1;
    for (int mode = 0; mode < modes; ++mode) {
      const double integral = w.moments.col(mode).sum();  // of 1, xi, eta over the footprint
      for (const Eigen::Vector3d& dir : directions) {
        Eigen::VectorXd row = Eigen::VectorXd::Zero(n);
        for (size_t i = 0; i < w.nodes.size(); ++i)
          row.segment<3>(3 * w.nodes[i]) = w.moments(static_cast<Eigen::Index>(i), mode) * dir;
        rows.push_back(row);
        targets.push_back(integral * dir.dot(ref.prescribed_m));
      }
    }
    r.jaw_nodes = static_cast<int>(w.nodes.size());
  }
  Eigen::MatrixXd c(static_cast<Eigen::Index>(rows.size()), n);
  for (size_t k = 0; k < rows.size(); ++k) c.row(static_cast<Eigen::Index>(k)) = rows[k].transpose();
  const Eigen::VectorXd g =
      Eigen::Map<const Eigen::VectorXd>(targets.data(), static_cast<Eigen::Index>(targets.size()));
  const Eigen::VectorXd jaw_forces = SolveWithMultipliers(bed_held, c, g);

  r.nodes = mesh.num_vertices();
  for (int node = 0; node < mesh.num_vertices(); ++node) r.force_N += jaw_forces.segment<3>(3 * node);
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

ToolLoadReference ReadGallbladderPressReference(const std::string& source_dir) {
  return ReadToolLoadReference(source_dir + "/tests/fem/data/gallbladder_press_reference.txt");
}

}  // namespace vesica::convergence
