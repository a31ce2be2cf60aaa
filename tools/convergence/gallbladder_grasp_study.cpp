#include "tools/convergence/gallbladder_grasp_study.h"

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "app/mesh_io/mesh_io.h"
#include "physics/fem/elastic_material.h"
#include "physics/fem/jaw_footprint.h"
#include "physics/fem/jaw_subgrid_compliance.h"
#include "physics/fem/quadratic_tet_mesh.h"
#include "physics/fem/small_strain_stiffness.h"
#include "physics/mesh/mesh_topology.h"

namespace vesica::convergence {

namespace {

// The jaw's outward normal: the pull's direction, the opposite of the press's.
Eigen::Vector3d JawNormal(const ToolLoadReference& ref, JawLoad load) {
  return (load == JawLoad::kPress ? -1.0 : 1.0) * ref.prescribed_m.normalized();
}

// The reference's jaw: its rectangle at its centre, the long side in the plane of `normal`.
physics::RectangularFootprint ReferenceJaw(const ToolLoadReference& ref, const Eigen::Vector3d& normal) {
  physics::RectangularFootprint jaw;
  jaw.centre_m = ref.centre_m;
  jaw.normal = normal;
  jaw.long_axis = (ref.jaw_long_axis - ref.jaw_long_axis.dot(normal) * normal).normalized();
  jaw.length_m = kJawLength_m;
  jaw.width_m = kJawWidth_m;
  return jaw;
}

// Minimises the elastic energy under C u = g (C: k x 3n) with the held dofs zero: the multipliers
// solve (C K^-1 C^T) mu = g, and the jaw's nodal forces on the body are C^T mu.
Eigen::VectorXd SolveWithMultipliers(const Eigen::SparseMatrix<double>& k, const std::vector<bool>& held_dof,
                                     const Eigen::MatrixXd& c, const Eigen::VectorXd& g) {
  return c.transpose() * physics::HeldRowCompliance(k, held_dof, c).ldlt().solve(g);
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
    case JawModel::kFootprintCells:
      return "footprint, 4 x 2 cells";
    case JawModel::kFootprintMeanWithSubgrid:
      return "footprint, mean, with the subgrid compliance (the trainer)";
  }
  return "?";
}

const char* TetFormulationName(TetFormulation formulation) {
  switch (formulation) {
    case TetFormulation::kLinear:
      return "linear tets";
    case TetFormulation::kNodalPressure:
      return "nodal-pressure tets";
    case TetFormulation::kQuadratic:
      return "quadratic tets";
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
                                             const ToolLoadReference& ref, JawModel jaw_model, JawLoad load,
                                             TetFormulation formulation, const physics::JawSubgridSettings& subgrid) {
  if (jaw_model == JawModel::kFootprintMeanWithSubgrid && formulation != TetFormulation::kLinear)
    throw std::invalid_argument("SolveGallbladderGrasp: the subgrid compliance corrects the linear tets only");
  const physics::TetBoundary boundary = physics::ExtractBoundary(mesh);
  const Eigen::Vector3d normal = JawNormal(ref, load);
  const physics::ElasticMaterial material{2300.0, 0.45, 1000.0};  // gallbladder paper, Table 1
  const bool quadratic = formulation == TetFormulation::kQuadratic;
  const physics::QuadraticTetMesh tet10 = quadratic ? physics::MakeQuadraticTetMesh(mesh) : physics::QuadraticTetMesh{};
  const Eigen::SparseMatrix<double> k = formulation == TetFormulation::kLinear
                                            ? physics::LinearTetStiffness(mesh, material)
                                        : quadratic ? physics::QuadraticTetStiffness(tet10, material)
                                                    : physics::NodalPressureTetStiffness(mesh, material);
  const int n = static_cast<int>(k.rows());
  const physics::Vertices& nodes = quadratic ? tet10.nodes : mesh.vertices;

  // The bed: the boundary nodes within 6 mm of a liver vertex; with quadratic tets also the
  // midpoints of the boundary triangles whose corners are all held (reference.py's "fixed").
  std::vector<bool> held_node(static_cast<size_t>(n / 3), false);
  std::vector<int> boundary_nodes;
  for (int s = 0; s < boundary.surface.num_vertices(); ++s) {
    const Eigen::RowVector3d p = boundary.surface.vertices.row(s);
    const int node = boundary.surface_to_volume(s);
    boundary_nodes.push_back(node);
    if ((liver.vertices.rowwise() - p).rowwise().norm().minCoeff() < kBedDistance_m)
      held_node[static_cast<size_t>(node)] = true;
  }
  if (quadratic)
    for (int f = 0; f < boundary.surface.num_triangles(); ++f) {
      int corner[3];
      for (int c = 0; c < 3; ++c) corner[c] = boundary.surface_to_volume(boundary.surface.triangles(f, c));
      const bool held = held_node[static_cast<size_t>(corner[0])] && held_node[static_cast<size_t>(corner[1])] &&
                        held_node[static_cast<size_t>(corner[2])];
      for (int c = 0; c < 3; ++c) {
        const int mid = tet10.Midpoint(corner[c], corner[(c + 1) % 3]);
        if (held) held_node[static_cast<size_t>(mid)] = true;
        boundary_nodes.push_back(mid);
      }
    }
  std::sort(boundary_nodes.begin(), boundary_nodes.end());
  boundary_nodes.erase(std::unique(boundary_nodes.begin(), boundary_nodes.end()), boundary_nodes.end());
  std::vector<bool> held_dof(static_cast<size_t>(n), false);
  for (int i = 0; i < n; ++i) held_dof[static_cast<size_t>(i)] = held_node[static_cast<size_t>(i / 3)];

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
    std::vector<int> inside;
    for (int node : boundary_nodes)
      if (!held_node[static_cast<size_t>(node)] && InJaw(nodes.row(node).transpose(), ref, load))
        inside.push_back(node);
    for (int node : inside)
      for (const Eigen::Vector3d& dir : directions) {
        Eigen::VectorXd row = Eigen::VectorXd::Zero(n);
        row.segment<3>(3 * node) = dir;
        rows.push_back(row);
        targets.push_back(dir.dot(ref.prescribed_m));
      }
    r.jaw_nodes = static_cast<int>(inside.size());
  } else {
    const physics::RectangularFootprint jaw = ReferenceJaw(ref, normal);
    // The footprints whose weighted mean the jaw moves: the rectangle, or each cell of its grid.
    std::vector<physics::RectangularFootprint> cells;
    const int cells_along = jaw_model == JawModel::kFootprintCells ? 4 : 1;
    const int cells_across = jaw_model == JawModel::kFootprintCells ? 2 : 1;
    const Eigen::Vector3d across = normal.cross(jaw.long_axis);
    for (int i = 0; i < cells_along; ++i)
      for (int j = 0; j < cells_across; ++j) {
        physics::RectangularFootprint cell = jaw;
        cell.length_m = jaw.length_m / cells_along;
        cell.width_m = jaw.width_m / cells_across;
        cell.centre_m += ((i + 0.5) * cell.length_m - 0.5 * jaw.length_m) * jaw.long_axis +
                         ((j + 0.5) * cell.width_m - 0.5 * jaw.width_m) * across;
        cells.push_back(cell);
      }
    const int modes = jaw_model == JawModel::kFootprintMeanAndTilt ? 3 : 1;
    std::vector<int> reached;
    for (const physics::RectangularFootprint& cell : cells) {
      const physics::FootprintWeights w = quadratic ? physics::ComputeQuadraticFootprintWeights(boundary, tet10, cell)
                                                    : physics::ComputeFootprintWeights(boundary, cell);
      reached.insert(reached.end(), w.nodes.begin(), w.nodes.end());
      for (int mode = 0; mode < modes; ++mode) {
        const double integral = w.moments.col(mode).sum();  // of 1, xi, eta over the footprint
        for (const Eigen::Vector3d& dir : directions) {
          Eigen::VectorXd row = Eigen::VectorXd::Zero(n);
          for (size_t i = 0; i < w.nodes.size(); ++i)
            row.segment<3>(3 * w.nodes[i]) += w.moments(static_cast<Eigen::Index>(i), mode) * dir;
          rows.push_back(row);
          targets.push_back(integral * dir.dot(ref.prescribed_m));
        }
      }
    }
    std::sort(reached.begin(), reached.end());
    r.jaw_nodes = static_cast<int>(std::unique(reached.begin(), reached.end()) - reached.begin());
  }
  Eigen::MatrixXd c(static_cast<Eigen::Index>(rows.size()), n);
  for (size_t i = 0; i < rows.size(); ++i) c.row(static_cast<Eigen::Index>(i)) = rows[i].transpose();
  const Eigen::VectorXd g =
      Eigen::Map<const Eigen::VectorXd>(targets.data(), static_cast<Eigen::Index>(targets.size()));
  Eigen::VectorXd jaw_forces;
  if (jaw_model != JawModel::kFootprintMeanWithSubgrid) {
    jaw_forces = SolveWithMultipliers(k, held_dof, c, g);
  } else {
    // The rows are the footprint's integrals (its area times the mean): the series compliance,
    // per unit mean displacement, enters scaled by the area squared.
    const physics::RectangularFootprint jaw = ReferenceJaw(ref, normal);
    const physics::JawSubgridCompliance sub =
        physics::ComputeJawSubgridCompliance(mesh, boundary, material, jaw, subgrid);
    const double area = physics::ComputeFootprintWeights(boundary, jaw).area_m2;
    Eigen::MatrixXd w = physics::HeldRowCompliance(k, held_dof, c);
    if (load == JawLoad::kPress)
      w(0, 0) += area * area * sub.subgrid_normal_m_per_N;
    else
      w += area * area * sub.subgrid_m_per_N;
    jaw_forces = c.transpose() * w.ldlt().solve(g);
  }

  r.nodes = mesh.num_vertices();
  r.dof_nodes = n / 3;
  for (int node = 0; node < n / 3; ++node) r.force_N += jaw_forces.segment<3>(3 * node);
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
