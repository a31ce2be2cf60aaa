#include "physics/fem/elastic_forces.h"

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

double CorotationalForces(const FemModel& m, const Eigen::VectorXd& u, Eigen::VectorXd* tangent,
                          Eigen::VectorXd* force) {
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
    const Eigen::Matrix3d r = RotationFromDeformationGradient(ds * e.rest_shape_inverse);
    Eigen::Vector3d d[4];  // unrotated displacement R^T x - X
    for (int a = 0; a < 4; ++a) d[a] = r.transpose() * x[a] - rest[a];
    for (int a = 0; a < 4; ++a) {
      Eigen::Vector3d local = Eigen::Vector3d::Zero();
      for (int b = 0; b < 4; ++b) {
        const Eigen::Matrix3d k = StiffnessBlock(e, m.lame_lambda_Pa, m.lame_mu_Pa, a, b);
        local += k * d[b];
        if (tangent) {
          const Eigen::Matrix3d kr = r * k * r.transpose();
          double* out = tangent->data() + m.pattern.block_slot[t][4 * a + b];
          const int stride = m.pattern.column_stride[node[b]];
          for (int c = 0; c < 3; ++c)
            for (int row = 0; row < 3; ++row) out[c * stride + row] += kr(row, c);
        }
      }
      energy += 0.5 * d[a].dot(local);
      force->segment<3>(3 * node[a]) += r * local;
    }
  }
  return energy;
}

}  // namespace

double ComputeElasticForces(const FemModel& model, const Eigen::VectorXd& u,
                            Eigen::VectorXd* tangent_values, Eigen::VectorXd* internal_force_N) {
  if (model.settings.element_model == ElementModel::kLinear)
    return LinearForces(model, u, tangent_values, internal_force_N);
  return CorotationalForces(model, u, tangent_values, internal_force_N);
}

}  // namespace vesica::physics
