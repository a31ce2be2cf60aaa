#include "physics/fem/fem_model.h"

#include <algorithm>
#include <sstream>
#include <string>
#include <vector>

#include "physics/fem/fem_error.h"
#include "physics/fem/time_integrator.h"
#include "physics/mesh/mesh_validation.h"

namespace vesica::physics {
namespace {

// The step's system S = c_M M + c_D D + K_t must stay within the range its solver computes in, or
// every step fails (a non-finite product, a norm that overflows): such settings are refused here,
// naming the setting whose term breaks the bound. The rotated-factor solver keeps its factor and
// the sweeps' rows of S in float unless told otherwise (FLT_MAX 3.4e38, and the sweeps' block
// inverses must not underflow); the double solvers square norms of S's products (|b|^2 overflows
// past 1e154).
constexpr double kMaxFloatSystemEntry = 1e35;
constexpr double kMaxDoubleSystemEntry = 1e150;

void CheckSystemScale(const FemModel& m) {
  const FemSettings& s = m.settings;
  const SystemCoefficients c = IntegratorCoefficients(s);
  const double mass_max = m.lumped_mass_kg.maxCoeff();
  const double stiffness_max = m.linear_stiffness_values.cwiseAbs().maxCoeff();
  const bool float_arrays =
      s.solver == LinearSolverKind::kRotatedFactorPcg &&
      (s.rotated_factor_single_precision || (s.rotated_factor_gauss_seidel && s.rotated_factor_float_sweeps));
  const double bound = float_arrays ? kMaxFloatSystemEntry : kMaxDoubleSystemEntry;
  auto check = [&](double entry, const char* kind, const char* field, double value) {
    if (entry <= bound) return;  // NaN fails too
    std::ostringstream os;
    os << s.body_name << ": " << kind << " " << field << " = " << value
       << " makes the step's system overflow (its entries reach " << entry << "; this solver needs them below " << bound
       << ")";
    throw FemError(os.str());
  };
  check(c.mass * mass_max, "setting", "time_step_s", s.time_step_s);
  check(stiffness_max, "material", "youngs_modulus_Pa", s.material.youngs_modulus_Pa);
  check(c.damping * s.rayleigh_mass_per_s * mass_max, "setting", "rayleigh_mass_per_s", s.rayleigh_mass_per_s);
  check(c.damping * s.rayleigh_stiffness_s * stiffness_max, "setting", "rayleigh_stiffness_s", s.rayleigh_stiffness_s);
}

}  // namespace

Eigen::Map<const Eigen::SparseMatrix<double>> PatternMatrix(const SparsePattern& p, const Eigen::VectorXd& values) {
  const auto& s = p.structure;
  return {s.rows(), s.cols(), s.nonZeros(), s.outerIndexPtr(), s.innerIndexPtr(), values.data()};
}

Eigen::VectorXd FemModel::MassTimes(const Eigen::VectorXd& x) const {
  if (uses_consistent_mass()) return PatternMatrix(pattern, consistent_mass_values) * x;
  return lumped_mass_kg.cwiseProduct(x);
}

double FemModel::MassQuadraticForm(const Eigen::VectorXd& x) const {
  if (uses_consistent_mass()) return x.dot(MassTimes(x));
  return x.dot(lumped_mass_kg.cwiseProduct(x));
}

Eigen::VectorXd FemModel::GravityForces(const Eigen::Vector3d& g) const {
  return MassTimes(g.replicate(num_nodes(), 1));
}

FemModel BuildFemModel(const TetrahedralMesh& mesh, const FemSettings& settings,
                       const std::vector<DirichletNode>& fixed_nodes) {
  ValidateSettings(settings);
  const std::string& name = settings.body_name;
  if (mesh.num_tets() == 0) throw FemError(name + ": mesh has no tetrahedra");
  // Names the body and the tet: "<body>: tetrahedron 17: is inverted ...", thrown as the FemError
  // every FEM entry point throws for bad input.
  try {
    ValidateTetrahedralMesh(mesh, name);
  } catch (const MeshError& e) {
    throw FemError(e.what());
  }

  FemModel m;
  m.settings = settings;
  m.rest_mesh = mesh;
  m.lame_lambda_Pa = LameLambda(settings.material);
  m.lame_mu_Pa = LameMu(settings.material);
  m.pattern = BuildSparsePattern(mesh);
  const int n = mesh.num_vertices();
  const Eigen::Index nnz = m.pattern.structure.nonZeros();
  const bool consistent = settings.mass_model == MassModel::kConsistent;
  m.lumped_mass_kg = Eigen::VectorXd::Zero(3 * n);
  m.linear_stiffness_values = Eigen::VectorXd::Zero(nnz);
  if (consistent) m.consistent_mass_values = Eigen::VectorXd::Zero(nnz);

  m.elements.reserve(mesh.num_tets());
  const double rho = settings.material.density_kg_per_m3;
  for (int t = 0; t < mesh.num_tets(); ++t) {
    auto x = [&](int a) { return Eigen::Vector3d(mesh.vertices.row(mesh.tets(t, a))); };
    m.elements.push_back(MakeTetElement(x(0), x(1), x(2), x(3)));
    const TetElement& e = m.elements.back();
    const double mass = rho * e.rest_volume_m3;
    for (int a = 0; a < 4; ++a) {
      m.lumped_mass_kg.segment<3>(3 * mesh.tets(t, a)).array() += mass / 4.0;
      for (int b = 0; b < 4; ++b) {
        const int nb = mesh.tets(t, b);
        const Eigen::Matrix3d k = StiffnessBlock(e, m.lame_lambda_Pa, m.lame_mu_Pa, a, b);
        for (int c = 0; c < 3; ++c)
          for (int r = 0; r < 3; ++r) m.linear_stiffness_values[m.pattern.Slot(t, a, b, nb, r, c)] += k(r, c);
        // Consistent linear-tet mass: rho V / 20 (1 + delta_ab) per axis.
        if (consistent)
          for (int r = 0; r < 3; ++r)
            m.consistent_mass_values[m.pattern.Slot(t, a, b, nb, r, r)] += mass / 20.0 * (a == b ? 2.0 : 1.0);
      }
    }
  }

  CheckSystemScale(m);

  m.element_batches = BuildElementBatches(mesh, m.elements);
  // A matrix-free body never assembles its tangent (ComputeElasticForces asked for one anyway takes
  // the scalar pass): no pair lists, ~2 MB and ~1 ms less for the 4,000-node SOFA beam.
  if (settings.element_model == ElementModel::kCorotational && !TangentIsMatrixFree(settings))
    m.tangent_blocks = BuildTangentBlocks(mesh, m.pattern, m.elements, m.lame_mu_Pa);

  m.free_dofs = Eigen::VectorXd::Ones(3 * n);
  for (const DirichletNode& f : fixed_nodes) {
    if (f.node < 0 || f.node >= n) {
      std::ostringstream os;
      os << name << ": fixed node " << f.node << " is out of range (mesh has " << n << " nodes)";
      throw FemError(os.str());
    }
    for (int axis = 0; axis < 3; ++axis)
      if (f.axes[axis]) m.free_dofs[3 * f.node + axis] = 0.0;
  }
  // A vertex no tet uses has no mass and no stiffness: unless it is held on every axis, the
  // system is singular every step.
  std::vector<char> used(static_cast<size_t>(n), 0);
  for (int t = 0; t < mesh.num_tets(); ++t)
    for (int a = 0; a < 4; ++a) used[static_cast<size_t>(mesh.tets(t, a))] = 1;
  for (int v = 0; v < n; ++v)
    if (!used[static_cast<size_t>(v)] && m.free_dofs.segment<3>(3 * v).any())
      throw FemError(name + ": vertex " + std::to_string(v) +
                     " belongs to no tetrahedron and is not fixed (it would have no mass and no stiffness)");
  for (int i = 0; i < 3 * n; ++i)
    if (m.free_dofs[i] == 0.0) m.fixed_dofs.push_back(i);
  const auto& s = m.pattern.structure;
  for (int col = 0; col < 3 * n; ++col)
    for (int k = s.outerIndexPtr()[col]; k < s.outerIndexPtr()[col + 1]; ++k)
      if (m.free_dofs[col] == 0.0 || m.free_dofs[s.innerIndexPtr()[k]] == 0.0) m.constrained_slots.push_back(k);
  return m;
}

}  // namespace vesica::physics
