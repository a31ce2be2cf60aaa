#include "physics/fem/small_strain_stiffness.h"

#include <array>
#include <stdexcept>
#include <string>
#include <vector>

#include "physics/fem/tet_element.h"

namespace vesica::physics {

namespace {

using Triplets = std::vector<Eigen::Triplet<double>>;

TetElement CheckedElement(const Vertices& x, int t, int n0, int n1, int n2, int n3) {
  const TetElement e =
      MakeTetElement(x.row(n0).transpose(), x.row(n1).transpose(), x.row(n2).transpose(), x.row(n3).transpose());
  if (!(e.rest_volume_m3 > 0.0))
    throw std::invalid_argument("small-strain stiffness: tet " + std::to_string(t) + " is inverted or flat (volume " +
                                std::to_string(e.rest_volume_m3) + " m^3)");
  return e;
}

// weight * (lambda ga gb^T + mu gb ga^T + mu (ga . gb) I): the isotropic block of grad N_a, grad N_b.
void AddBlock(Triplets& k, int node_a, int node_b, const Eigen::Vector3d& ga, const Eigen::Vector3d& gb, double lambda,
              double mu, double weight) {
  Eigen::Matrix3d block = lambda * ga * gb.transpose() + mu * gb * ga.transpose();
  block.diagonal().array() += mu * ga.dot(gb);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) k.emplace_back(3 * node_a + i, 3 * node_b + j, weight * block(i, j));
}

Eigen::SparseMatrix<double> Assemble(int num_nodes, const Triplets& k) {
  Eigen::SparseMatrix<double> out(3 * num_nodes, 3 * num_nodes);
  out.setFromTriplets(k.begin(), k.end());
  return out;
}

// Element gradients and the element lists each formulation needs, with lambda replaced by
// lambda_element (the nodal-pressure tet keeps only the deviatoric part per element).
Triplets LinearTetTriplets(const TetrahedralMesh& mesh, double lambda_element, double mu) {
  Triplets k;
  k.reserve(static_cast<size_t>(mesh.num_tets()) * 144);
  for (int t = 0; t < mesh.num_tets(); ++t) {
    const TetElement e =
        CheckedElement(mesh.vertices, t, mesh.tets(t, 0), mesh.tets(t, 1), mesh.tets(t, 2), mesh.tets(t, 3));
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b)
        AddBlock(k, mesh.tets(t, a), mesh.tets(t, b), e.shape_gradients[a], e.shape_gradients[b], lambda_element, mu,
                 e.rest_volume_m3);
  }
  return k;
}

}  // namespace

Eigen::SparseMatrix<double> LinearTetStiffness(const TetrahedralMesh& mesh, const ElasticMaterial& material) {
  return Assemble(mesh.num_vertices(), LinearTetTriplets(mesh, LameLambda(material), LameMu(material)));
}

Eigen::SparseMatrix<double> NodalPressureTetStiffness(const TetrahedralMesh& mesh, const ElasticMaterial& material) {
  const double mu = LameMu(material);
  const double kappa = LameLambda(material) + 2.0 * mu / 3.0;  // bulk modulus
  // Deviatoric per element: lambda - kappa = -2 mu / 3 in place of lambda.
  Triplets k = LinearTetTriplets(mesh, -2.0 * mu / 3.0, mu);
  // Volumetric per node: theta_a = b_a . u, b_a = sum_e (V_e / 4 / V_a) div_e, div_e the element's
  // divergence row (grad N_i on node i's dofs); energy kappa / 2 V_a theta_a^2.
  const int n = mesh.num_vertices();
  std::vector<double> node_volume(static_cast<size_t>(n), 0.0);
  std::vector<std::vector<int>> tets_of(static_cast<size_t>(n));
  std::vector<TetElement> elements;
  elements.reserve(static_cast<size_t>(mesh.num_tets()));
  for (int t = 0; t < mesh.num_tets(); ++t) {
    elements.push_back(
        CheckedElement(mesh.vertices, t, mesh.tets(t, 0), mesh.tets(t, 1), mesh.tets(t, 2), mesh.tets(t, 3)));
    for (int c = 0; c < 4; ++c) {
      node_volume[static_cast<size_t>(mesh.tets(t, c))] += 0.25 * elements.back().rest_volume_m3;
      tets_of[static_cast<size_t>(mesh.tets(t, c))].push_back(t);
    }
  }
  std::vector<std::pair<int, double>> b;  // (dof, coefficient), duplicates summed by the assembly
  for (int a = 0; a < n; ++a) {
    b.clear();
    const double v_a = node_volume[static_cast<size_t>(a)];
    for (int t : tets_of[static_cast<size_t>(a)]) {
      const TetElement& e = elements[static_cast<size_t>(t)];
      const double share = 0.25 * e.rest_volume_m3 / v_a;
      for (int c = 0; c < 4; ++c)
        for (int i = 0; i < 3; ++i) b.emplace_back(3 * mesh.tets(t, c) + i, share * e.shape_gradients[c][i]);
    }
    // Merge the duplicates first: the outer product's size is the square of b's.
    Eigen::SparseVector<double> merged(3 * n);
    for (const auto& [dof, value] : b) merged.coeffRef(dof) += value;
    for (Eigen::SparseVector<double>::InnerIterator p(merged); p; ++p)
      for (Eigen::SparseVector<double>::InnerIterator q(merged); q; ++q)
        k.emplace_back(static_cast<int>(p.index()), static_cast<int>(q.index()), kappa * v_a * p.value() * q.value());
  }
  return Assemble(n, k);
}

Eigen::SparseMatrix<double> QuadraticTetStiffness(const QuadraticTetMesh& mesh, const ElasticMaterial& material) {
  const double lambda = LameLambda(material), mu = LameMu(material);
  // 4-point Gauss rule on the tet (degree 2), barycentric (alpha, beta, beta, beta) and permutations.
  constexpr double kAlpha = 0.5854101966249685, kBeta = 0.1381966011250105;
  Triplets k;
  k.reserve(static_cast<size_t>(mesh.tets.rows()) * 900);
  Triplets element;
  for (int t = 0; t < mesh.tets.rows(); ++t) {
    const TetElement e =
        CheckedElement(mesh.nodes, t, mesh.tets(t, 0), mesh.tets(t, 1), mesh.tets(t, 2), mesh.tets(t, 3));
    const std::array<Eigen::Vector3d, 4>& g = e.shape_gradients;  // grad L_k, constant on a straight tet
    element.clear();  // local 30 x 30, summed over the points before it goes into k
    for (int q = 0; q < 4; ++q) {
      std::array<double, 4> l;
      l.fill(kBeta);
      l[static_cast<size_t>(q)] = kAlpha;
      // grad N at the point: corners (4 L_k - 1) g_k, midpoints 4 (L_i g_j + L_j g_i).
      std::array<Eigen::Vector3d, 10> grad;
      for (size_t c = 0; c < 4; ++c) grad[c] = (4.0 * l[c] - 1.0) * g[c];
      for (size_t m = 0; m < 6; ++m) {
        const auto i = static_cast<size_t>(kTet10Edges[m][0]), j = static_cast<size_t>(kTet10Edges[m][1]);
        grad[4 + m] = 4.0 * (l[i] * g[j] + l[j] * g[i]);
      }
      for (int a = 0; a < 10; ++a)
        for (int c = 0; c < 10; ++c)
          AddBlock(element, a, c, grad[static_cast<size_t>(a)], grad[static_cast<size_t>(c)], lambda, mu,
                   0.25 * e.rest_volume_m3);
    }
    Eigen::Matrix<double, 30, 30> local = Eigen::Matrix<double, 30, 30>::Zero();
    for (const auto& entry : element) local(entry.row(), entry.col()) += entry.value();
    for (int a = 0; a < 30; ++a)
      for (int c = 0; c < 30; ++c)
        k.emplace_back(3 * mesh.tets(t, a / 3) + a % 3, 3 * mesh.tets(t, c / 3) + c % 3, local(a, c));
  }
  return Assemble(mesh.num_nodes(), k);
}

}  // namespace vesica::physics
