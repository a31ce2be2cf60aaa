#include "physics/bem/bem_matrices.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <thread>
#include <vector>

#include <Eigen/Geometry>

#include "physics/bem/kelvin_solution.h"
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

// Influence of one element on one collocation point: 3x3 blocks per element corner.
struct ElementInfluence {
  std::array<Eigen::Matrix3d, 3> h;
  std::array<Eigen::Matrix3d, 3> g;
  void Clear() {
    for (int c = 0; c < 3; ++c) h[c].setZero(), g[c].setZero();
  }
};

class RowAssembler {
 public:
  RowAssembler(const std::vector<ElementGeometry>& elements, const ElasticMaterial& material,
               const BemQuadratureOptions& options)
      : elements_(elements),
        mu_(LameMu(material)),
        nu_(material.poisson_ratio),
        options_(options) {
    for (int c = 0; c < 3; ++c) duffy_[c] = TriangleDuffy(c, options.duffy_order);
  }

  // Fills rows 3i..3i+2 of H and G for collocation node i. The row is accumulated in contiguous
  // per-node 3x3 blocks (cache-resident) and copied once: scattering each element's blocks
  // straight into the column-major matrices missed the cache on every column.
  void AssembleRow(int i, const Eigen::Vector3d& source, Eigen::MatrixXd& H, Eigen::MatrixXd& G) {
    const std::size_t n = static_cast<std::size_t>(H.cols() / 3);
    row_h_.assign(n, Eigen::Matrix3d::Zero());
    row_g_.assign(n, Eigen::Matrix3d::Zero());
    for (const ElementGeometry& e : elements_) {
      influence_.Clear();
      const int corner = e.nodes[0] == i ? 0 : e.nodes[1] == i ? 1 : e.nodes[2] == i ? 2 : -1;
      if (corner >= 0) {
        Accumulate(e, source, duffy_[corner], kIdentityCorners, /*skip_h_corner=*/corner, 1.0);
      } else {
        Regular(e, source, kIdentityCorners, 0);
      }
      for (int c = 0; c < 3; ++c) {
        const std::size_t j = static_cast<std::size_t>(e.nodes[c]);
        row_h_[j] += influence_.h[c];
        row_g_[j] += influence_.g[c];
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
    Accumulate(e, source, rule, sub, /*skip_h_corner=*/-1, scale * scale);
  }

  // Adds sum_k w_k area N_c(x_k) {T*, U*}(x_k - source) for corners c of element e; the rule lives
  // on sub-triangle `sub` whose area is area_fraction of the element.
  void Accumulate(const ElementGeometry& e, const Eigen::Vector3d& source,
                  const TriangleQuadrature& rule, const Corners& sub, int skip_h_corner,
                  double area_fraction) {
    for (const TriangleQuadraturePoint& q : rule) {
      std::array<double, 3> shape{};
      for (int a = 0; a < 3; ++a)
        for (int c = 0; c < 3; ++c) shape[c] += q.barycentric[a] * sub[a][c];
      const Eigen::Vector3d x =
          shape[0] * e.corners[0] + shape[1] * e.corners[1] + shape[2] * e.corners[2];
      const Eigen::Vector3d r = x - source;
      const double w = q.weight * e.area * area_fraction;
      const Eigen::Matrix3d u_star = KelvinDisplacement(r, mu_, nu_);
      const Eigen::Matrix3d t_star = KelvinTraction(r, e.normal, nu_);
      for (int c = 0; c < 3; ++c) {
        influence_.g[c] += (w * shape[c]) * u_star;
        if (c != skip_h_corner) influence_.h[c] += (w * shape[c]) * t_star;
      }
    }
  }

  const std::vector<ElementGeometry>& elements_;
  double mu_, nu_;
  BemQuadratureOptions options_;
  std::array<TriangleQuadrature, 3> duffy_;
  ElementInfluence influence_;
  std::vector<Eigen::Matrix3d> row_h_, row_g_;
};

}  // namespace

BemMatrices AssembleBemMatrices(const TriangleMesh& surface, const ElasticMaterial& material,
                                const BemQuadratureOptions& options) {
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
  BemMatrices m{Eigen::MatrixXd::Zero(dofs, dofs), Eigen::MatrixXd::Zero(dofs, dofs)};
  // Blocks of consecutive rows per task keep threads off each other's cache lines.
  constexpr int kRowsPerTask = 16;
  std::atomic<int> next_task{0};
  auto worker = [&] {
    RowAssembler assembler(elements, material, options);
    for (;;) {
      const int first = kRowsPerTask * next_task.fetch_add(1);
      if (first >= surface.num_vertices()) return;
      const int last = std::min(first + kRowsPerTask, surface.num_vertices());
      for (int i = first; i < last; ++i)
        assembler.AssembleRow(i, surface.vertices.row(i).transpose(), m.H, m.G);
    }
  };
  const unsigned threads = std::max(1u, std::thread::hardware_concurrency());
  std::vector<std::thread> pool;
  for (unsigned t = 1; t < threads; ++t) pool.emplace_back(worker);
  worker();
  for (std::thread& t : pool) t.join();
  return m;
}

}  // namespace vesica::physics
