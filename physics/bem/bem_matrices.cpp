#include "physics/bem/bem_matrices.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <numbers>
#include <thread>
#include <vector>

#include <Eigen/Geometry>

#include "physics/bem/triangle_quadrature.h"
#include "physics/mesh/mesh_validation.h"

namespace vesica::physics {
namespace {

struct ElementGeometry {
  std::array<int, 3> nodes;
  std::array<Eigen::Vector3d, 3> corners;
  Eigen::Vector3d normal;  // unit, outward
  double area;
  double size;  // longest edge
};

// Assembles one collocation row at a time into contiguous per-node 3x3 blocks (cache-resident),
// copied into the column-major H and G once per row: scattering element blocks straight into the
// big matrices missed the cache on every column.
class RowAssembler {
 public:
  RowAssembler(const std::vector<ElementGeometry>& elements, const ElasticMaterial& material,
               const BemQuadratureOptions& options)
      : elements_(elements), options_(options) {
    const double mu = LameMu(material), nu = material.poisson_ratio;
    u_scale_ = 1.0 / (16.0 * std::numbers::pi * mu * (1.0 - nu));
    u_diagonal_ = 3.0 - 4.0 * nu;
    t_scale_ = -1.0 / (8.0 * std::numbers::pi * (1.0 - nu));
    t_a_ = 1.0 - 2.0 * nu;
    for (int c = 0; c < 3; ++c) duffy_[c] = TriangleDuffy(c, options.duffy_order);
  }

  // Fills rows 3i..3i+2 of H and G for collocation node i.
  void AssembleRow(int i, const Eigen::Vector3d& source, Eigen::MatrixXd& H, Eigen::MatrixXd& G) {
    const std::size_t n = static_cast<std::size_t>(H.cols() / 3);
    row_h_.assign(n, Eigen::Matrix3d::Zero());
    row_g_.assign(n, Eigen::Matrix3d::Zero());
    for (const ElementGeometry& e : elements_) {
      const int corner = e.nodes[0] == i ? 0 : e.nodes[1] == i ? 1 : e.nodes[2] == i ? 2 : -1;
      // On the elements touching i, U* ~ 1/r and N_j T* ~ 1/r for j != i are integrable with
      // Duffy's rule; whatever lands in H's own block (i, i) is overwritten below.
      if (corner >= 0) {
        Accumulate(e, source, duffy_[corner], kIdentityCorners, 1.0);
      } else {
        Regular(e, source, kIdentityCorners, 0);
      }
    }
    // Rigid translation u = const gives zero traction, so H times it vanishes row by row.
    Eigen::Matrix3d diagonal = Eigen::Matrix3d::Zero();
    for (std::size_t j = 0; j < n; ++j)
      if (j != static_cast<std::size_t>(i)) diagonal -= row_h_[j];
    row_h_[static_cast<std::size_t>(i)] = diagonal;
    for (std::size_t j = 0; j < n; ++j) {
      H.block<3, 3>(3 * i, 3 * static_cast<Eigen::Index>(j)) = row_h_[j];
      G.block<3, 3>(3 * i, 3 * static_cast<Eigen::Index>(j)) = row_g_[j];
    }
  }

 private:
  using Corners = std::array<std::array<double, 3>, 3>;  // sub-triangle corners, barycentric
  static constexpr Corners kIdentityCorners{{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};

  void Regular(const ElementGeometry& e, const Eigen::Vector3d& source, const Corners& sub,
               int depth) {
    const double scale = 1.0 / double(1 << depth);
    const double size = e.size * scale;
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    for (int a = 0; a < 3; ++a)
      for (int c = 0; c < 3; ++c) centroid += (sub[a][c] / 3.0) * e.corners[c];
    const double distance = (centroid - source).norm();
    if (distance < options_.near_ratio * size && depth < options_.max_subdivision) {
      std::array<double, 3> m01, m12, m20;
      for (int c = 0; c < 3; ++c) {
        m01[c] = 0.5 * (sub[0][c] + sub[1][c]);
        m12[c] = 0.5 * (sub[1][c] + sub[2][c]);
        m20[c] = 0.5 * (sub[2][c] + sub[0][c]);
      }
      Regular(e, source, {sub[0], m01, m20}, depth + 1);
      Regular(e, source, {m01, sub[1], m12}, depth + 1);
      Regular(e, source, {m20, m12, sub[2]}, depth + 1);
      Regular(e, source, {m01, m12, m20}, depth + 1);
      return;
    }
    const TriangleQuadrature& rule =
        distance > options_.far_ratio * size ? TriangleGauss3() : TriangleGauss7();
    Accumulate(e, source, rule, sub, scale * scale);
  }

  // Adds sum_k w_k area N_c(x_k) {T*, U*}(x_k - source) into the row blocks of the corners c of
  // element e; the rule lives on sub-triangle `sub` whose area is area_fraction of the element.
  // The Kelvin kernels (kelvin_solution.h) are written out here so that r, 1/r and r,i r,j are
  // shared between U* and T* in this innermost loop.
  void Accumulate(const ElementGeometry& e, const Eigen::Vector3d& source,
                  const TriangleQuadrature& rule, const Corners& sub, double area_fraction) {
    const double nx = e.normal.x(), ny = e.normal.y(), nz = e.normal.z();
    double g_sum[3][6] = {};  // U* is symmetric: xx yy zz xy xz yz
    double h_sum[3][9] = {};  // T*, row-major
    for (const TriangleQuadraturePoint& q : rule) {
      double shape[3] = {0, 0, 0};
      for (int a = 0; a < 3; ++a)
        for (int c = 0; c < 3; ++c) shape[c] += q.barycentric[a] * sub[a][c];
      const Eigen::Vector3d x =
          shape[0] * e.corners[0] + shape[1] * e.corners[1] + shape[2] * e.corners[2];
      const double rx = x.x() - source.x(), ry = x.y() - source.y(), rz = x.z() - source.z();
      const double inv_r = 1.0 / std::sqrt(rx * rx + ry * ry + rz * rz);
      const double dx = rx * inv_r, dy = ry * inv_r, dz = rz * inv_r;
      const double drdn = dx * nx + dy * ny + dz * nz;
      const double w = q.weight * e.area * area_fraction;
      // U* = u_scale / r [(3-4nu) I + d d^T]
      const double wu = w * u_scale_ * inv_r;
      const double u[6] = {wu * (u_diagonal_ + dx * dx), wu * (u_diagonal_ + dy * dy),
                           wu * (u_diagonal_ + dz * dz), wu * dx * dy,
                           wu * dx * dz,                 wu * dy * dz};
      // T* = t_scale / r^2 [drdn ((1-2nu) I + 3 d d^T) - (1-2nu)(d n^T - n d^T)]
      const double wt = w * t_scale_ * inv_r * inv_r;
      const double p = drdn * t_a_, q3 = 3.0 * drdn;
      const double cxy = t_a_ * (dx * ny - nx * dy), cxz = t_a_ * (dx * nz - nx * dz),
                   cyz = t_a_ * (dy * nz - ny * dz);
      const double t[9] = {wt * (q3 * dx * dx + p), wt * (q3 * dx * dy - cxy), wt * (q3 * dx * dz - cxz),
                           wt * (q3 * dy * dx + cxy), wt * (q3 * dy * dy + p), wt * (q3 * dy * dz - cyz),
                           wt * (q3 * dz * dx + cxz), wt * (q3 * dz * dy + cyz), wt * (q3 * dz * dz + p)};
      for (int c = 0; c < 3; ++c) {
        for (int k = 0; k < 6; ++k) g_sum[c][k] += shape[c] * u[k];
        for (int k = 0; k < 9; ++k) h_sum[c][k] += shape[c] * t[k];
      }
    }
    for (int c = 0; c < 3; ++c) {
      Eigen::Matrix3d& g = row_g_[static_cast<std::size_t>(e.nodes[c])];
      Eigen::Matrix3d& h = row_h_[static_cast<std::size_t>(e.nodes[c])];
      g(0, 0) += g_sum[c][0], g(1, 1) += g_sum[c][1], g(2, 2) += g_sum[c][2];
      g(0, 1) += g_sum[c][3], g(1, 0) += g_sum[c][3];
      g(0, 2) += g_sum[c][4], g(2, 0) += g_sum[c][4];
      g(1, 2) += g_sum[c][5], g(2, 1) += g_sum[c][5];
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b) h(a, b) += h_sum[c][3 * a + b];
    }
  }

  const std::vector<ElementGeometry>& elements_;
  BemQuadratureOptions options_;
  double u_scale_, u_diagonal_, t_scale_, t_a_;
  std::array<TriangleQuadrature, 3> duffy_;
  std::vector<Eigen::Matrix3d> row_h_, row_g_;
};

}  // namespace

BemMatrices AssembleBemMatrices(const TriangleMesh& surface, const ElasticMaterial& material,
                                const BemQuadratureOptions& options, const std::function<void(double)>& on_progress) {
  ValidateBemMaterial(material);
  ValidateTriangleMesh(surface, "BEM surface", SurfaceRequirement::kClosed);
  std::vector<ElementGeometry> elements(static_cast<std::size_t>(surface.num_triangles()));
  for (int f = 0; f < surface.num_triangles(); ++f) {
    ElementGeometry& e = elements[static_cast<std::size_t>(f)];
    for (int c = 0; c < 3; ++c) {
      e.nodes[c] = surface.triangles(f, c);
      e.corners[c] = surface.vertices.row(e.nodes[c]).transpose();
    }
    const Eigen::Vector3d cross = (e.corners[1] - e.corners[0]).cross(e.corners[2] - e.corners[0]);
    e.area = 0.5 * cross.norm();
    e.normal = cross.normalized();
    e.size = std::max({(e.corners[1] - e.corners[0]).norm(), (e.corners[2] - e.corners[1]).norm(),
                       (e.corners[0] - e.corners[2]).norm()});
  }

  const Eigen::Index dofs = 3 * surface.num_vertices();
  BemMatrices m{Eigen::MatrixXd(dofs, dofs), Eigen::MatrixXd(dofs, dofs)};  // every row is written
  // Blocks of consecutive rows per task keep threads off each other's cache lines.
  constexpr int kRowsPerTask = 16;
  std::atomic<int> next_task{0}, rows_done{0};
  const double rows = surface.num_vertices();
  double next_report = 0.05;
  auto worker = [&](bool reports) {
    RowAssembler assembler(elements, material, options);
    for (;;) {
      const int first = kRowsPerTask * next_task.fetch_add(1);
      if (first >= surface.num_vertices()) return;
      const int last = std::min(first + kRowsPerTask, surface.num_vertices());
      for (int i = first; i < last; ++i)
        assembler.AssembleRow(i, surface.vertices.row(i).transpose(), m.H, m.G);
      const double done = (rows_done += last - first) / rows;
      if (reports && on_progress && done >= next_report && done < 1.0) {
        on_progress(done);
        next_report = done + 0.05;
      }
    }
  };
  const unsigned threads = std::max(1u, std::thread::hardware_concurrency());
  std::vector<std::thread> pool;
  for (unsigned t = 1; t < threads; ++t) pool.emplace_back(worker, false);
  worker(true);  // only the calling thread reports: the callback need not be thread-safe
  for (std::thread& t : pool) t.join();
  if (on_progress) on_progress(1.0);
  return m;
}

}  // namespace vesica::physics
