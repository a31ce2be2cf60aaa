#include "physics/bem/bem_reference_problem.h"

#include <utility>

#include <Eigen/Geometry>

#include "physics/bem/bem_errors.h"
#include "physics/bem/dense_lu_solve.h"

namespace vesica::physics {

BemNodeLayout MakeBemNodeLayout(const TriangleMesh& surface, const std::string& source) {
  const int n = surface.num_vertices();
  if (surface.vertex_labels.size() != n)
    throw BemError(source + ": vertex_labels has " + std::to_string(surface.vertex_labels.size()) +
                   " entries for " + std::to_string(n) +
                   " vertices; the BEM needs the fixed region (kLabelFixed)");
  BemNodeLayout layout;
  layout.free_index = Eigen::VectorXi::Constant(n, -1);
  for (int i = 0; i < n; ++i) {
    if (surface.vertex_labels(i) & kLabelFixed) {
      layout.fixed_nodes.push_back(i);
    } else {
      layout.free_index(i) = static_cast<int>(layout.free_nodes.size());
      layout.free_nodes.push_back(i);
    }
  }
  // Three non-collinear fixed points stop every rigid motion.
  bool spans_plane = false;
  if (layout.fixed_nodes.size() >= 3) {
    const Eigen::Vector3d p0 = surface.vertices.row(layout.fixed_nodes[0]).transpose();
    Eigen::Vector3d axis = Eigen::Vector3d::Zero();
    for (int i : layout.fixed_nodes) {
      const Eigen::Vector3d d = surface.vertices.row(i).transpose() - p0;
      if (d.norm() > axis.norm()) axis = d;
    }
    const double extent = axis.norm();
    for (int i : layout.fixed_nodes) {
      const Eigen::Vector3d d = surface.vertices.row(i).transpose() - p0;
      if (extent > 0 && axis.normalized().cross(d).norm() > 1e-6 * extent) spans_plane = true;
    }
  }
  if (!spans_plane)
    throw BemError(source + ": fixed region (kLabelFixed) has " +
                   std::to_string(layout.fixed_nodes.size()) +
                   " vertices; at least 3 non-collinear ones are needed to stop rigid motion");
  if (layout.free_nodes.empty()) throw BemError(source + ": every vertex is fixed; nothing can move");
  return layout;
}

Eigen::MatrixXd ComputeGreensFunctions(BemMatrices&& matrices, const BemNodeLayout& layout) {
  Eigen::MatrixXd& a0 = matrices.H;
  Eigen::MatrixXd& g = matrices.G;
  Eigen::MatrixXd xi(g.rows(), 3 * static_cast<Eigen::Index>(layout.free_nodes.size()));
  for (std::size_t f = 0; f < layout.free_nodes.size(); ++f)
    xi.middleCols<3>(3 * static_cast<Eigen::Index>(f)) = g.middleCols<3>(3 * layout.free_nodes[f]);
  for (int i : layout.fixed_nodes) a0.middleCols<3>(3 * i) = -g.middleCols<3>(3 * i);
  g.resize(0, 0);  // release before the factorisation
  SolveDenseInPlace(a0, xi, "BEM reference problem (fixed region + free surface)");
  return xi;
}

}  // namespace vesica::physics
