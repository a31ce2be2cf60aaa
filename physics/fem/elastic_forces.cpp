#include "physics/fem/elastic_forces.h"

#include <Eigen/Geometry>
#include <Eigen/LU>

#include "physics/fem/element_rotation.h"

namespace vesica::physics {

void SymmetricPatternMultiply(const SparsePattern& p, const Eigen::VectorXd& values,
                              const Eigen::VectorXd& x, Eigen::VectorXd& y) {
  // Column j of a symmetric matrix is its row j: a gather loop per output entry.
  const int n = static_cast<int>(p.structure.cols());
  const int* outer = p.structure.outerIndexPtr();
  const int* inner = p.structure.innerIndexPtr();
  const double* v = values.data();
  y.resize(n);
  for (int j = 0; j < n; ++j) {
    double sum = 0.0;
    for (int k = outer[j]; k < outer[j + 1]; ++k) sum += v[k] * x[inner[k]];
    y[j] = sum;
  }
}

namespace {

double LinearForces(const FemModel& m, const Eigen::VectorXd& u, Eigen::VectorXd* tangent,
                    Eigen::VectorXd* force) {
  if (tangent) *tangent = m.linear_stiffness_values;
  SymmetricPatternMultiply(m.pattern, m.linear_stiffness_values, u, *force);
  return 0.5 * u.dot(*force);
}

// Below this det F the warm-started iteration is not trusted (inversion): the SVD decides.
constexpr double kMinDetForIteration = 0.2;

double CorotationalForces(const FemModel& m, const Eigen::VectorXd& u, Eigen::VectorXd* tangent,
                          Eigen::VectorXd* force, std::vector<Eigen::Vector4d>* cache) {
  if (cache && static_cast<int>(cache->size()) != m.rest_mesh.num_tets())
    cache->assign(m.rest_mesh.num_tets(), Eigen::Vector4d(0, 0, 0, 1));
  const auto& mesh = m.rest_mesh;
  force->setZero(u.size());
  if (tangent) tangent->setZero(m.pattern.structure.nonZeros());
  double energy = 0.0;
  for (int t = 0; t < mesh.num_tets(); ++t) {
    const TetElement& e = m.elements[t];
    int node[4];
    Eigen::Vector3d rest[4], x[4];
    for (int a = 0; a < 4; ++a) {
      node[a] = mesh.tets(t, a);
      rest[a] = mesh.vertices.row(node[a]).transpose();
      x[a] = rest[a] + u.segment<3>(3 * node[a]);
    }
    Eigen::Matrix3d ds;
    ds << x[1] - x[0], x[2] - x[0], x[3] - x[0];
    const Eigen::Matrix3d f = ds * e.rest_shape_inverse;
    Eigen::Matrix3d r;
    if (cache && f.determinant() > kMinDetForIteration) {
      r = RotationByQuaternionIteration(f, (*cache)[t], 30);  // stops early once converged
    } else {
      r = RotationFromDeformationGradient(f);
      if (cache) {
        const Eigen::Quaterniond q(r);
        (*cache)[t] = q.coeffs();
      }
    }
    Eigen::Vector3d d[4];  // unrotated displacement R^T x - X
    for (int a = 0; a < 4; ++a) d[a] = r.transpose() * x[a] - rest[a];
    Eigen::Matrix3d k[4][4];  // K_ba = K_ab^T: build the upper blocks only
    for (int a = 0; a < 4; ++a)
      for (int b = a; b < 4; ++b) {
        k[a][b] = StiffnessBlock(e, m.lame_lambda_Pa, m.lame_mu_Pa, a, b);
        if (b != a) k[b][a] = k[a][b].transpose();
      }
    for (int a = 0; a < 4; ++a) {
      const Eigen::Vector3d local = k[a][0] * d[0] + k[a][1] * d[1] + k[a][2] * d[2] + k[a][3] * d[3];
      energy += 0.5 * d[a].dot(local);
      force->segment<3>(3 * node[a]) += r * local;
    }
    if (!tangent) continue;
    for (int a = 0; a < 4; ++a)
      for (int b = a; b < 4; ++b) {
        const Eigen::Matrix3d kr = r * k[a][b] * r.transpose();
        double* out_ab = tangent->data() + m.pattern.block_slot[t][4 * a + b];
        const int stride_b = m.pattern.column_stride[node[b]];
        for (int c = 0; c < 3; ++c)
          for (int row = 0; row < 3; ++row) out_ab[c * stride_b + row] += kr(row, c);
        if (b == a) continue;
        double* out_ba = tangent->data() + m.pattern.block_slot[t][4 * b + a];
        const int stride_a = m.pattern.column_stride[node[a]];
        for (int c = 0; c < 3; ++c)
          for (int row = 0; row < 3; ++row) out_ba[c * stride_a + row] += kr(c, row);
      }
  }
  return energy;
}

}  // namespace

double ComputeElasticForces(const FemModel& model, const Eigen::VectorXd& u,
                            Eigen::VectorXd* tangent_values, Eigen::VectorXd* internal_force_N,
                            std::vector<Eigen::Vector4d>* rotation_cache) {
  if (model.settings.element_model == ElementModel::kLinear)
    return LinearForces(model, u, tangent_values, internal_force_N);
  return CorotationalForces(model, u, tangent_values, internal_force_N, rotation_cache);
}

}  // namespace vesica::physics
