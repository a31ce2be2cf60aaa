#include "physics/fem/jaw_subgrid_compliance.h"

#include <Eigen/Cholesky>
#include <Eigen/CholmodSupport>
#include <Eigen/Eigenvalues>
#include <Eigen/SparseCore>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <vector>

#include "physics/fem/fem_error.h"
#include "physics/fem/quadratic_tet_mesh.h"
#include "physics/fem/small_strain_stiffness.h"

namespace vesica::physics {

namespace {

std::uint64_t FaceKey(std::array<int, 3> f) {
  std::sort(f.begin(), f.end());
  return (static_cast<std::uint64_t>(f[0]) << 42) | (static_cast<std::uint64_t>(f[1]) << 21) |
         static_cast<std::uint64_t>(f[2]);
}

}  // namespace

Eigen::MatrixXd HeldRowCompliance(const Eigen::SparseMatrix<double>& k, const std::vector<bool>& held_dof,
                                  const Eigen::MatrixXd& c) {
  std::vector<int> free_index(held_dof.size(), -1);
  int n_free = 0;
  for (size_t i = 0; i < held_dof.size(); ++i)
    if (!held_dof[i]) free_index[i] = n_free++;
  std::vector<Eigen::Triplet<double>> kept;
  kept.reserve(static_cast<size_t>(k.nonZeros()) / 2 + 1);
  for (int col = 0; col < k.outerSize(); ++col)
    for (Eigen::SparseMatrix<double>::InnerIterator e(k, col); e; ++e) {
      const int r = free_index[static_cast<size_t>(e.row())], q = free_index[static_cast<size_t>(e.col())];
      if (r >= 0 && q >= 0 && r >= q) kept.emplace_back(r, q, e.value());
    }
  Eigen::SparseMatrix<double> k_ff(n_free, n_free);
  k_ff.setFromTriplets(kept.begin(), kept.end());
  Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>, Eigen::Lower> cholesky(k_ff);
  if (cholesky.info() != Eigen::Success)
    throw FemError("HeldRowCompliance: the stiffness on the free dofs is not positive definite (too few held)");
  Eigen::MatrixXd c_f = Eigen::MatrixXd::Zero(n_free, c.rows());
  for (size_t i = 0; i < held_dof.size(); ++i)
    if (free_index[i] >= 0) c_f.row(free_index[i]) = c.col(static_cast<Eigen::Index>(i)).transpose();
  const Eigen::MatrixXd x = cholesky.solve(c_f);
  const Eigen::MatrixXd w = c_f.transpose() * x;
  return 0.5 * (w + w.transpose());
}

namespace {

// Rows moving each footprint's weighted mean along each direction: one row per (footprint,
// direction), over `dofs` dofs.
Eigen::MatrixXd MeanRows(const std::vector<FootprintWeights>& footprints,
                         const std::vector<Eigen::Vector3d>& directions, Eigen::Index dofs) {
  Eigen::MatrixXd c = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(footprints.size() * directions.size()), dofs);
  Eigen::Index row = 0;
  for (const FootprintWeights& f : footprints)
    for (const Eigen::Vector3d& d : directions) {
      for (size_t i = 0; i < f.nodes.size(); ++i)
        c.block<1, 3>(row, 3 * f.nodes[i]) += f.moments(static_cast<Eigen::Index>(i), 0) / f.area_m2 * d.transpose();
      ++row;
    }
  return c;
}

// The compliance of a rigid jaw whose every row (grouped per footprint, `per` rows each) moves
// with it: with G stacking the identity per footprint, K = G^T W^-1 G, and the compliance K^-1.
Eigen::MatrixXd RigidJawCompliance(const Eigen::MatrixXd& w, int per) {
  const Eigen::Index groups = w.rows() / per;
  Eigen::MatrixXd g = Eigen::MatrixXd::Zero(w.rows(), per);
  for (Eigen::Index i = 0; i < groups; ++i) g.middleRows(i * per, per).setIdentity();
  const Eigen::MatrixXd k = g.transpose() * w.ldlt().solve(g);
  return k.inverse();
}

}  // namespace

JawSubgridCompliance ComputeJawSubgridCompliance(const TetrahedralMesh& mesh, const TetBoundary& boundary,
                                                 const ElasticMaterial& material, const RectangularFootprint& jaw,
                                                 const JawSubgridSettings& settings) {
  if (!(std::isfinite(settings.patch_radius_m) && settings.patch_radius_m > 0))
    throw std::invalid_argument("ComputeJawSubgridCompliance: patch_radius_m must be finite and > 0");
  if (settings.cells_along < 1 || settings.cells_across < 1)
    throw std::invalid_argument("ComputeJawSubgridCompliance: cells_along and cells_across must be >= 1");
  JawSubgridCompliance out;
  const FootprintWeights whole = ComputeFootprintWeights(boundary, jaw);  // throws for a bad jaw
  for (size_t i = 0; i < whole.nodes.size(); ++i) {
    out.nodes.push_back(whole.nodes[i]);
    out.weights.push_back(whole.moments(static_cast<Eigen::Index>(i), 0) / whole.area_m2);
  }

  // The patch: tets with a corner within the radius, renumbered; its cut faces (shared with a
  // tet outside) are held.
  const double r2 = settings.patch_radius_m * settings.patch_radius_m;
  std::vector<int> patch_tets, local(static_cast<size_t>(mesh.num_vertices()), -1);
  std::vector<int> tet_local(static_cast<size_t>(mesh.num_tets()), -1);
  TetrahedralMesh patch;
  std::vector<int> global_of;
  for (int t = 0; t < mesh.num_tets(); ++t) {
    bool near = false;
    for (int c = 0; c < 4 && !near; ++c)
      near = (mesh.vertices.row(mesh.tets(t, c)).transpose() - jaw.centre_m).squaredNorm() <= r2;
    if (!near) continue;
    tet_local[static_cast<size_t>(t)] = static_cast<int>(patch_tets.size());
    patch_tets.push_back(t);
    for (int c = 0; c < 4; ++c) {
      int& l = local[static_cast<size_t>(mesh.tets(t, c))];
      if (l < 0) {
        l = static_cast<int>(global_of.size());
        global_of.push_back(mesh.tets(t, c));
      }
    }
  }
  patch.vertices.resize(static_cast<Eigen::Index>(global_of.size()), 3);
  for (size_t i = 0; i < global_of.size(); ++i)
    patch.vertices.row(static_cast<Eigen::Index>(i)) = mesh.vertices.row(global_of[i]);
  patch.tets.resize(static_cast<Eigen::Index>(patch_tets.size()), 4);
  for (size_t t = 0; t < patch_tets.size(); ++t)
    for (int c = 0; c < 4; ++c)
      patch.tets(static_cast<Eigen::Index>(t), c) = local[static_cast<size_t>(mesh.tets(patch_tets[t], c))];
  out.patch_tets = patch.num_tets();

  std::unordered_map<std::uint64_t, int> outside_faces;  // faces of tets outside the patch
  for (int t = 0; t < mesh.num_tets(); ++t) {
    if (tet_local[static_cast<size_t>(t)] >= 0) continue;
    for (int k = 0; k < 4; ++k) {
      const std::array<int, 3> corners = TetFaceCorners(k);
      ++outside_faces[FaceKey({mesh.tets(t, corners[0]), mesh.tets(t, corners[1]), mesh.tets(t, corners[2])})];
    }
  }
  std::vector<std::array<int, 3>> cut_faces;  // in patch numbers
  for (int t : patch_tets)
    for (int k = 0; k < 4; ++k) {
      const std::array<int, 3> corners = TetFaceCorners(k);
      const std::array<int, 3> f{mesh.tets(t, corners[0]), mesh.tets(t, corners[1]), mesh.tets(t, corners[2])};
      if (outside_faces.count(FaceKey(f)))
        cut_faces.push_back(
            {local[static_cast<size_t>(f[0])], local[static_cast<size_t>(f[1])], local[static_cast<size_t>(f[2])]});
    }
  if (cut_faces.empty())
    throw FemError("ComputeJawSubgridCompliance: the patch of radius " + std::to_string(settings.patch_radius_m) +
                   " m is the whole body (no cut faces to hold)");

  // The body's surface under the patch, in patch numbers (only faces of patch tets).
  TetBoundary patch_boundary;
  patch_boundary.surface.vertices = boundary.surface.vertices;
  patch_boundary.surface_to_volume = Eigen::VectorXi::Constant(boundary.surface.num_vertices(), -1);
  std::vector<Eigen::Index> kept;
  for (int f = 0; f < boundary.surface.num_triangles(); ++f)
    if (tet_local[static_cast<size_t>(boundary.face_tet[f])] >= 0) kept.push_back(f);
  patch_boundary.surface.triangles.resize(static_cast<Eigen::Index>(kept.size()), 3);
  for (size_t i = 0; i < kept.size(); ++i) {
    patch_boundary.surface.triangles.row(static_cast<Eigen::Index>(i)) = boundary.surface.triangles.row(kept[i]);
    for (int c = 0; c < 3; ++c) {
      const int s = boundary.surface.triangles(kept[i], c);
      patch_boundary.surface_to_volume[s] = local[static_cast<size_t>(boundary.surface_to_volume[s])];
    }
  }
  const FootprintWeights linear_footprint = ComputeFootprintWeights(patch_boundary, jaw);
  if (std::abs(linear_footprint.area_m2 - whole.area_m2) > 1e-9 * whole.area_m2)
    throw std::invalid_argument("ComputeJawSubgridCompliance: patch_radius_m " +
                                std::to_string(settings.patch_radius_m) + " does not cover the jaw's footprint");

  const std::vector<Eigen::Vector3d> axes{Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(), Eigen::Vector3d::UnitZ()};
  const std::vector<Eigen::Vector3d> normal_only{jaw.normal};

  // The trainer's element: linear tets, the footprint's mean.
  {
    const Eigen::SparseMatrix<double> k = LinearTetStiffness(patch, material);
    std::vector<bool> held(static_cast<size_t>(k.rows()), false);
    for (const auto& f : cut_faces)
      for (int node : f)
        for (int a = 0; a < 3; ++a) held[static_cast<size_t>(3 * node + a)] = true;
    const Eigen::MatrixXd w = HeldRowCompliance(k, held, MeanRows({linear_footprint}, axes, k.rows()));
    out.linear_m_per_N = w;
    out.linear_normal_m_per_N = jaw.normal.dot(out.linear_m_per_N * jaw.normal);
  }

  // The continuum's: 10-node tets, the jaw as a grid of cells.
  {
    const QuadraticTetMesh q = MakeQuadraticTetMesh(patch);
    const Eigen::SparseMatrix<double> k = QuadraticTetStiffness(q, material);
    std::vector<bool> held(static_cast<size_t>(k.rows()), false);
    auto hold = [&](int node) {
      for (int a = 0; a < 3; ++a) held[static_cast<size_t>(3 * node + a)] = true;
    };
    for (const auto& f : cut_faces)
      for (int c = 0; c < 3; ++c) {
        hold(f[static_cast<size_t>(c)]);
        hold(q.Midpoint(f[static_cast<size_t>(c)], f[static_cast<size_t>((c + 1) % 3)]));
      }
    out.patch_dofs = static_cast<int>(std::count(held.begin(), held.end(), false));
    std::vector<FootprintWeights> cells;
    const Eigen::Vector3d across = jaw.normal.cross(jaw.long_axis);
    for (int i = 0; i < settings.cells_along; ++i)
      for (int j = 0; j < settings.cells_across; ++j) {
        RectangularFootprint cell = jaw;
        cell.length_m = jaw.length_m / settings.cells_along;
        cell.width_m = jaw.width_m / settings.cells_across;
        cell.centre_m += ((i + 0.5) * cell.length_m - 0.5 * jaw.length_m) * jaw.long_axis +
                         ((j + 0.5) * cell.width_m - 0.5 * jaw.width_m) * across;
        try {
          cells.push_back(ComputeQuadraticFootprintWeights(patch_boundary, q, cell));
        } catch (const std::invalid_argument&) {
          // No surface under this cell (the jaw overhangs an edge of the body): it holds nothing.
        }
      }
    if (cells.empty()) throw std::invalid_argument("ComputeJawSubgridCompliance: no surface under the jaw's cells");
    out.quadratic_m_per_N = RigidJawCompliance(HeldRowCompliance(k, held, MeanRows(cells, axes, k.rows())), 3);
    out.quadratic_normal_m_per_N =
        RigidJawCompliance(HeldRowCompliance(k, held, MeanRows(cells, normal_only, k.rows())), 1)(0, 0);
  }

  const Eigen::Matrix3d diff = out.quadratic_m_per_N - out.linear_m_per_N;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(0.5 * (diff + diff.transpose()));
  out.subgrid_m_per_N =
      eig.eigenvectors() * eig.eigenvalues().cwiseMax(0.0).asDiagonal() * eig.eigenvectors().transpose();
  out.subgrid_normal_m_per_N = std::max(0.0, out.quadratic_normal_m_per_N - out.linear_normal_m_per_N);
  return out;
}

}  // namespace vesica::physics
