#include "physics/bem/ellipsoid_surface.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <vector>

namespace vesica::physics {

TriangleMesh MakeEllipsoidSurface(const Eigen::Vector3d& semi_axes, int num_vertices) {
  if (num_vertices < 8) throw std::invalid_argument("MakeEllipsoidSurface: num_vertices < 8");
  const double pi = std::numbers::pi;
  // On a unit sphere with ~uniform spacing h: rings ~ pi / h, ring k holds ~ 2 pi sin(theta) / h.
  const int ring_vertices = num_vertices - 2;
  const int rings = std::max(1, static_cast<int>(std::lround(std::sqrt(pi * ring_vertices / 4.0))));
  std::vector<double> theta(static_cast<std::size_t>(rings)), weight(static_cast<std::size_t>(rings));
  double weight_sum = 0;
  for (int k = 0; k < rings; ++k) {
    theta[static_cast<std::size_t>(k)] = pi * (k + 1) / (rings + 1);
    weight[static_cast<std::size_t>(k)] = std::sin(theta[static_cast<std::size_t>(k)]);
    weight_sum += weight[static_cast<std::size_t>(k)];
  }
  std::vector<int> count(static_cast<std::size_t>(rings));
  int assigned = 0;
  for (int k = 0; k < rings; ++k) {
    count[static_cast<std::size_t>(k)] =
        std::max(3, static_cast<int>(std::floor(ring_vertices * weight[static_cast<std::size_t>(k)] / weight_sum)));
    assigned += count[static_cast<std::size_t>(k)];
  }
  // Hand out (or take back) the rounding remainder around the equator.
  for (int k = rings / 2, step = 0; assigned != ring_vertices; ++step) {
    const int ring = (k + (step % 2 ? -(step + 1) / 2 : step / 2) % rings + rings) % rings;
    if (assigned < ring_vertices) {
      ++count[static_cast<std::size_t>(ring)], ++assigned;
    } else if (count[static_cast<std::size_t>(ring)] > 3) {
      --count[static_cast<std::size_t>(ring)], --assigned;
    }
  }

  std::vector<Eigen::Vector3d> v;
  std::vector<int> first(static_cast<std::size_t>(rings));
  v.emplace_back(0, 0, 1);  // north pole
  for (int k = 0; k < rings; ++k) {
    first[static_cast<std::size_t>(k)] = static_cast<int>(v.size());
    const int m = count[static_cast<std::size_t>(k)];
    const double offset = 0.5 * (k % 2);  // stagger rings for better triangles
    for (int j = 0; j < m; ++j) {
      const double phi = 2 * pi * (j + offset) / m, t = theta[static_cast<std::size_t>(k)];
      v.emplace_back(std::sin(t) * std::cos(phi), std::sin(t) * std::sin(phi), std::cos(t));
    }
  }
  v.emplace_back(0, 0, -1);  // south pole
  const int south = static_cast<int>(v.size()) - 1;

  std::vector<std::array<int, 3>> f;
  auto angle = [&](int k, int j) {
    return 2 * pi * (j + 0.5 * (k % 2)) / count[static_cast<std::size_t>(k)];
  };
  const int m0 = count[0];
  for (int j = 0; j < m0; ++j) f.push_back({0, first[0] + j, first[0] + (j + 1) % m0});
  for (int k = 0; k + 1 < rings; ++k) {
    const int ma = count[static_cast<std::size_t>(k)], mb = count[static_cast<std::size_t>(k + 1)];
    const int fa = first[static_cast<std::size_t>(k)], fb = first[static_cast<std::size_t>(k + 1)];
    // Zip the two rings by increasing angle, starting from the pair of first vertices.
    int i = 0, j = 0;
    while (i < ma || j < mb) {
      const double next_a = angle(k, i + 1), next_b = angle(k + 1, j + 1);
      if (j >= mb || (i < ma && next_a <= next_b)) {
        f.push_back({fa + i % ma, fb + j % mb, fa + (i + 1) % ma});
        ++i;
      } else {
        f.push_back({fa + i % ma, fb + j % mb, fb + (j + 1) % mb});
        ++j;
      }
    }
  }
  const int ml = count.back(), fl = first.back();
  for (int j = 0; j < ml; ++j) f.push_back({south, fl + (j + 1) % ml, fl + j});

  TriangleMesh mesh;
  mesh.vertices.resize(static_cast<Eigen::Index>(v.size()), 3);
  for (std::size_t i = 0; i < v.size(); ++i)
    mesh.vertices.row(static_cast<Eigen::Index>(i)) = v[i].cwiseProduct(semi_axes).transpose();
  mesh.triangles.resize(static_cast<Eigen::Index>(f.size()), 3);
  for (std::size_t i = 0; i < f.size(); ++i)
    mesh.triangles.row(static_cast<Eigen::Index>(i)) << f[i][0], f[i][1], f[i][2];
  mesh.vertex_labels = Eigen::VectorXi::Zero(mesh.num_vertices());
  if (EnclosedVolume(mesh) < 0) mesh.triangles.col(1).swap(mesh.triangles.col(2));
  return mesh;
}

}  // namespace vesica::physics
