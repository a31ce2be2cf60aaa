#include "physics/calot/tube_rod.h"

#include <Eigen/Geometry>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace vesica::physics::calot {

// Newton's method on implicit Euler's incremental potential (docs/calot.md): the sparsity of the
// 3N by 3N Hessian (nodes within two of each other) is analysed once, the values refactorised
// each iteration.
struct TubeRod::Solver {
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> factor;
  bool analysed = false;
};

namespace {

void CheckNode(int node, int count, const char* what) {
  if (node < 0 || node >= count)
    throw std::out_of_range(std::string("TubeRod::") + what + ": no node " + std::to_string(node) + " (have " +
                            std::to_string(count) + ")");
}

RodPoints Zeros(Eigen::Index rows) { return RodPoints::Zero(rows, 3); }

}  // namespace

TubeRod::TubeRod(const RodPoints& rest_points_m, std::vector<double> material_coordinates_m,
                 const TubeMaterial& material, const TubeRodSettings& settings)
    : TubeRod(rest_points_m, rest_points_m, Zeros(rest_points_m.rows()), std::move(material_coordinates_m), material,
              settings) {}

TubeRod::TubeRod(const RodPoints& rest_points_m, const RodPoints& positions_m, const RodPoints& velocities_m_per_s,
                 std::vector<double> material_coordinates_m, const TubeMaterial& material,
                 const TubeRodSettings& settings)
    : rest_points_(rest_points_m),
      positions_(positions_m),
      velocities_(velocities_m_per_s),
      material_coordinates_(std::move(material_coordinates_m)),
      material_(material),
      settings_(settings) {
  Initialise();
}

TubeRod::~TubeRod() = default;
TubeRod::TubeRod(TubeRod&&) noexcept = default;
TubeRod& TubeRod::operator=(TubeRod&&) noexcept = default;

void TubeRod::Initialise() {
  const Eigen::Index n = rest_points_.rows();
  if (n < 2) throw std::invalid_argument("TubeRod: needs at least 2 nodes, got " + std::to_string(n));
  if (positions_.rows() != n || velocities_.rows() != n)
    throw std::invalid_argument("TubeRod: positions and velocities must have as many rows as the rest points (" +
                                std::to_string(n) + ")");
  if (!rest_points_.allFinite() || !positions_.allFinite() || !velocities_.allFinite())
    throw std::invalid_argument("TubeRod: points must be finite");
  ValidateTubeMaterial(material_, "TubeRod");
  if (!(settings_.time_step_s > 0)) throw std::invalid_argument("TubeRod: settings.time_step_s must be > 0");
  if (settings_.solver_iterations < 1) throw std::invalid_argument("TubeRod: settings.solver_iterations must be >= 1");
  if (!(settings_.coupling_stiffness_N_per_m > 0))
    throw std::invalid_argument("TubeRod: settings.coupling_stiffness_N_per_m must be > 0");

  rest_lengths_.resize(static_cast<std::size_t>(n - 1));
  for (Eigen::Index i = 0; i + 1 < n; ++i) {
    rest_lengths_[static_cast<std::size_t>(i)] = (rest_points_.row(i + 1) - rest_points_.row(i)).norm();
    if (!(rest_lengths_[static_cast<std::size_t>(i)] > 1e-6))
      throw std::invalid_argument("TubeRod: rest points " + std::to_string(i) + " and " + std::to_string(i + 1) +
                                  " are closer than 1e-6 m");
  }
  if (material_coordinates_.empty()) {
    material_coordinates_.push_back(0.0);
    for (double l : rest_lengths_) material_coordinates_.push_back(material_coordinates_.back() + l);
  }
  if (static_cast<Eigen::Index>(material_coordinates_.size()) != n)
    throw std::invalid_argument("TubeRod: " + std::to_string(material_coordinates_.size()) +
                                " material coordinates for " + std::to_string(n) + " nodes");
  for (std::size_t i = 1; i < material_coordinates_.size(); ++i)
    if (!(material_coordinates_[i] > material_coordinates_[i - 1]))
      throw std::invalid_argument("TubeRod: material coordinates must increase (index " + std::to_string(i) + ")");

  const double area = WallArea_m2(material_), inertia = SecondMomentOfArea_m4(material_);
  const double rho = LinearDensity_kg_per_m(material_), youngs = material_.youngs_modulus_Pa;
  masses_.assign(static_cast<std::size_t>(n), 0.0);
  stretch_weights_.resize(rest_lengths_.size());
  for (std::size_t i = 0; i < rest_lengths_.size(); ++i) {
    masses_[i] += 0.5 * rho * rest_lengths_[i];
    masses_[i + 1] += 0.5 * rho * rest_lengths_[i];
    stretch_weights_[i] = youngs * area / rest_lengths_[i];  // EA / L0
  }
  // Bending at interior node i: v_i = e_i / l_i - e_{i-1} / l_{i-1} (difference of unit tangents,
  // linear in x), energy EI / (2 lbar_i) |v_i - R v0_i|^2 with lbar the Voronoi length.
  bending_weights_.assign(static_cast<std::size_t>(n), 0.0);
  rest_curvature_ = Zeros(n);
  rest_tangents_ = Zeros(n);
  for (Eigen::Index i = 1; i + 1 < n; ++i) {
    const double l0 = rest_lengths_[static_cast<std::size_t>(i - 1)], l1 = rest_lengths_[static_cast<std::size_t>(i)];
    bending_weights_[static_cast<std::size_t>(i)] = youngs * inertia / (0.5 * (l0 + l1));
    const Eigen::Vector3d t0 = (rest_points_.row(i) - rest_points_.row(i - 1)).transpose() / l0;
    const Eigen::Vector3d t1 = (rest_points_.row(i + 1) - rest_points_.row(i)).transpose() / l1;
    rest_curvature_.row(i) = (t1 - t0).transpose();
    const Eigen::Vector3d tangent = t0 + t1;
    rest_tangents_.row(i) = (tangent.norm() > 1e-12 ? tangent.normalized() : t1).transpose();
  }
  holds_.assign(static_cast<std::size_t>(n), NodeHold::kFree);
  external_forces_N_ = Zeros(n);
  coupling_targets_ = Zeros(n);
  Factorise();
}

void TubeRod::Factorise() { solver_ = std::make_unique<Solver>(); }

void TubeRod::HoldFixed(int node) {
  CheckNode(node, num_nodes(), "HoldFixed");
  holds_[static_cast<std::size_t>(node)] = NodeHold::kFixed;
  velocities_.row(node).setZero();
  Factorise();
}

void TubeRod::SetHeldPosition(int node, const Eigen::Vector3d& p_W_m) {
  CheckNode(node, num_nodes(), "SetHeldPosition");
  if (holds_[static_cast<std::size_t>(node)] != NodeHold::kFixed)
    throw std::logic_error("TubeRod::SetHeldPosition: node " + std::to_string(node) + " is not held fixed");
  velocities_.row(node) = (p_W_m.transpose() - positions_.row(node)) / settings_.time_step_s;
  positions_.row(node) = p_W_m.transpose();
}

void TubeRod::CoupleToTarget(int node, const Eigen::Vector3d& p_Target_W_m) {
  CheckNode(node, num_nodes(), "CoupleToTarget");
  holds_[static_cast<std::size_t>(node)] = NodeHold::kCoupled;
  coupling_targets_.row(node) = p_Target_W_m.transpose();
  Factorise();
}

void TubeRod::SetCouplingTarget(int node, const Eigen::Vector3d& p_Target_W_m) {
  CheckNode(node, num_nodes(), "SetCouplingTarget");
  if (holds_[static_cast<std::size_t>(node)] != NodeHold::kCoupled)
    throw std::logic_error("TubeRod::SetCouplingTarget: node " + std::to_string(node) + " is not coupled");
  coupling_targets_.row(node) = p_Target_W_m.transpose();
}

Eigen::Vector3d TubeRod::coupling_target_m(int node) const {
  CheckNode(node, num_nodes(), "coupling_target_m");
  return coupling_targets_.row(node).transpose();
}

Eigen::Vector3d TubeRod::CouplingForceOnTarget_N(int node) const {
  CheckNode(node, num_nodes(), "CouplingForceOnTarget_N");
  if (holds_[static_cast<std::size_t>(node)] != NodeHold::kCoupled) return Eigen::Vector3d::Zero();
  return settings_.coupling_stiffness_N_per_m * (positions_.row(node) - coupling_targets_.row(node)).transpose();
}

void TubeRod::Release(int node) {
  CheckNode(node, num_nodes(), "Release");
  holds_[static_cast<std::size_t>(node)] = NodeHold::kFree;
  Factorise();
}

void TubeRod::SetExternalForce(int node, const Eigen::Vector3d& force_N) {
  CheckNode(node, num_nodes(), "SetExternalForce");
  external_forces_N_.row(node) = force_N.transpose();
}

void TubeRod::ClearExternalForces() { external_forces_N_.setZero(); }

Eigen::Vector3d TubeRod::BendingTarget(int i, const RodPoints& x) const {
  const Eigen::Vector3d v0 = rest_curvature_.row(i).transpose();
  if (v0.squaredNorm() == 0.0) return v0;
  // The rest curvature carried along by the rotation that takes the rest tangent to the current
  // one (parallel transport; the rod has no twist, see docs/calot.md).
  const Eigen::Vector3d e0 = (x.row(i) - x.row(i - 1)).transpose(), e1 = (x.row(i + 1) - x.row(i)).transpose();
  Eigen::Vector3d tangent = e0.normalized() + e1.normalized();
  if (tangent.norm() < 1e-12) return v0;
  const Eigen::Quaterniond rotation =
      Eigen::Quaterniond::FromTwoVectors(rest_tangents_.row(i).transpose(), tangent.normalized());
  return rotation * v0;
}

void TubeRod::Step() {
  const int n = num_nodes();
  const double h = settings_.time_step_s, alpha = material_.mass_damping_per_s;
  const RodPoints previous = positions_;
  RodPoints inertial(n, 3);  // y = x_n + h v_n + h^2 (f/m + g)
  for (int i = 0; i < n; ++i)
    inertial.row(i) = previous.row(i) + h * velocities_.row(i) +
                      (h * h) * (external_forces_N_.row(i) / masses_[static_cast<std::size_t>(i)] +
                                 settings_.gravity_m_per_s2.transpose());
  // The rest curvature's rotated targets, frozen over the step (from the step's start), so the
  // step minimises a fixed potential.
  RodPoints bend_targets = Zeros(n);
  for (int i = 1; i + 1 < n; ++i) bend_targets.row(i) = BendingTarget(i, previous).transpose();
  auto is_fixed = [&](int i) { return holds_[static_cast<std::size_t>(i)] == NodeHold::kFixed; };
  auto bend_coefficients = [&](int i) {
    const double l0 = rest_lengths_[static_cast<std::size_t>(i - 1)], l1 = rest_lengths_[static_cast<std::size_t>(i)];
    return Eigen::Vector3d(1.0 / l0, -(1.0 / l0 + 1.0 / l1), 1.0 / l1);
  };
  // g(x) = sum m/(2h^2)|x - y|^2 + alpha m/(2h)|x - x_n|^2 + E_stretch + E_bend + E_coupling.
  auto potential = [&](const RodPoints& x) {
    double g = 0.0;
    for (int i = 0; i < n; ++i) {
      const double m = masses_[static_cast<std::size_t>(i)];
      g += 0.5 * m / (h * h) * (x.row(i) - inertial.row(i)).squaredNorm() +
           0.5 * alpha * m / h * (x.row(i) - previous.row(i)).squaredNorm();
      if (holds_[static_cast<std::size_t>(i)] == NodeHold::kCoupled)
        g += 0.5 * settings_.coupling_stiffness_N_per_m * (x.row(i) - coupling_targets_.row(i)).squaredNorm();
    }
    for (int i = 0; i + 1 < n; ++i) {
      const double stretch = (x.row(i + 1) - x.row(i)).norm() - rest_lengths_[static_cast<std::size_t>(i)];
      g += 0.5 * stretch_weights_[static_cast<std::size_t>(i)] * stretch * stretch;
    }
    for (int i = 1; i + 1 < n; ++i) {
      const Eigen::Vector3d c = bend_coefficients(i);
      const Eigen::RowVector3d r = c(0) * x.row(i - 1) + c(1) * x.row(i) + c(2) * x.row(i + 1) - bend_targets.row(i);
      g += 0.5 * bending_weights_[static_cast<std::size_t>(i)] * r.squaredNorm();
    }
    return g;
  };

  RodPoints x = previous + h * velocities_;  // warm start: the inertial guess; held nodes stay put
  for (int i = 0; i < n; ++i)
    if (is_fixed(i)) x.row(i) = previous.row(i);
  const Eigen::Index dofs = 3 * n;
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(static_cast<std::size_t>(n) * 9 * 5 + 16);
  auto add_block = [&](int a, int b, const Eigen::Matrix3d& block) {
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) triplets.emplace_back(3 * a + r, 3 * b + c, block(r, c));
  };
  for (int iteration = 0; iteration < settings_.solver_iterations; ++iteration) {
    RodPoints gradient = Zeros(n);
    std::vector<Eigen::Matrix3d> diagonal(static_cast<std::size_t>(n), Eigen::Matrix3d::Zero());
    triplets.clear();
    for (int i = 0; i < n; ++i) {
      const double m = masses_[static_cast<std::size_t>(i)];
      gradient.row(i) = m / (h * h) * (x.row(i) - inertial.row(i)) + alpha * m / h * (x.row(i) - previous.row(i));
      double d = m / (h * h) + alpha * m / h;
      if (holds_[static_cast<std::size_t>(i)] == NodeHold::kCoupled) {
        gradient.row(i) += settings_.coupling_stiffness_N_per_m * (x.row(i) - coupling_targets_.row(i));
        d += settings_.coupling_stiffness_N_per_m;
      }
      diagonal[static_cast<std::size_t>(i)] = d * Eigen::Matrix3d::Identity();
    }
    for (int i = 0; i + 1 < n; ++i) {  // stretch, with its Hessian kept positive (compression: axial part only)
      const Eigen::Vector3d e = (x.row(i + 1) - x.row(i)).transpose();
      const double length = std::max(e.norm(), 1e-12), rest = rest_lengths_[static_cast<std::size_t>(i)];
      const double w = stretch_weights_[static_cast<std::size_t>(i)];
      const Eigen::Vector3d u = e / length;
      const Eigen::RowVector3d force = (w * (length - rest) * u).transpose();
      gradient.row(i) -= force;
      gradient.row(i + 1) += force;
      const Eigen::Matrix3d uu = u * u.transpose();
      const Eigen::Matrix3d k = w * (uu + std::max(0.0, 1.0 - rest / length) * (Eigen::Matrix3d::Identity() - uu));
      diagonal[static_cast<std::size_t>(i)] += k;
      diagonal[static_cast<std::size_t>(i) + 1] += k;
      const bool free_pair = !is_fixed(i) && !is_fixed(i + 1);
      add_block(i, i + 1, free_pair ? (-k).eval() : Eigen::Matrix3d::Zero());
      add_block(i + 1, i, free_pair ? (-k).eval() : Eigen::Matrix3d::Zero());
    }
    for (int i = 1; i + 1 < n; ++i) {  // bending: quadratic, w A^T A
      const Eigen::Vector3d c = bend_coefficients(i);
      const double w = bending_weights_[static_cast<std::size_t>(i)];
      const Eigen::RowVector3d r = c(0) * x.row(i - 1) + c(1) * x.row(i) + c(2) * x.row(i + 1) - bend_targets.row(i);
      for (int a = 0; a < 3; ++a) {
        gradient.row(i - 1 + a) += w * c(a) * r;
        diagonal[static_cast<std::size_t>(i - 1 + a)] += w * c(a) * c(a) * Eigen::Matrix3d::Identity();
        for (int b = 0; b < 3; ++b) {
          if (a == b) continue;
          const bool free_pair = !is_fixed(i - 1 + a) && !is_fixed(i - 1 + b);
          add_block(i - 1 + a, i - 1 + b, (free_pair ? w * c(a) * c(b) : 0.0) * Eigen::Matrix3d::Identity());
        }
      }
    }
    for (int i = 0; i < n; ++i) {
      if (is_fixed(i)) {
        gradient.row(i).setZero();
        diagonal[static_cast<std::size_t>(i)].setIdentity();
      }
      add_block(i, i, diagonal[static_cast<std::size_t>(i)]);
    }
    Eigen::SparseMatrix<double> hessian(dofs, dofs);
    hessian.setFromTriplets(triplets.begin(), triplets.end());
    if (!solver_->analysed) {
      solver_->factor.analyzePattern(hessian);
      solver_->analysed = true;
    }
    solver_->factor.factorize(hessian);
    if (solver_->factor.info() != Eigen::Success)
      throw std::runtime_error("TubeRod::Step: the Hessian could not be factorised");
    Eigen::VectorXd g_flat(dofs);
    for (int i = 0; i < n; ++i) g_flat.segment<3>(3 * i) = gradient.row(i).transpose();
    const Eigen::VectorXd step_flat = -solver_->factor.solve(g_flat);
    RodPoints direction(n, 3);
    for (int i = 0; i < n; ++i) direction.row(i) = step_flat.segment<3>(3 * i).transpose();
    // Backtracking line search: the potential must go down (Armijo).
    const double slope = g_flat.dot(step_flat), g0 = potential(x);
    double t = 1.0;
    RodPoints trial = x + direction;
    while (potential(trial) > g0 + 1e-4 * t * slope && t > 1e-4) {
      t *= 0.5;
      trial = x + t * direction;
    }
    x = trial;
    if (t * direction.cwiseAbs().maxCoeff() < 1e-10) break;  // converged to 0.1 nm
  }
  for (int i = 0; i < n; ++i)
    if (!is_fixed(i)) velocities_.row(i) = (x.row(i) - previous.row(i)) / h;
  positions_ = x;
}

double TubeRod::PushOutOfSphere(const Eigen::Vector3d& c, double radius_m) {
  if (!(radius_m >= 0) || !c.allFinite())
    throw std::invalid_argument("TubeRod::PushOutOfSphere: centre must be finite and radius >= 0");
  const double reach = radius_m + material_.outer_radius_m;
  double deepest = 0.0;
  for (int pass = 0; pass < 2; ++pass)
    for (int i = 0; i + 1 < num_nodes(); ++i) {
      const Eigen::Vector3d a = positions_.row(i).transpose(),
                            d = (positions_.row(i + 1) - positions_.row(i)).transpose();
      const double t = d.squaredNorm() > 0 ? std::clamp((c - a).dot(d) / d.squaredNorm(), 0.0, 1.0) : 0.0;
      const Eigen::Vector3d q = a + t * d;
      const double distance = (q - c).norm(), depth = reach - distance;
      if (depth <= 0) continue;
      if (pass == 0) deepest = std::max(deepest, depth);
      Eigen::Vector3d normal = distance > 1e-12 ? ((q - c) / distance).eval() : d.unitOrthogonal();
      const double w0 = holds_[static_cast<std::size_t>(i)] == NodeHold::kFixed ? 0.0 : 1.0 - t;
      const double w1 = holds_[static_cast<std::size_t>(i + 1)] == NodeHold::kFixed ? 0.0 : t;
      const double denominator = w0 * w0 + w1 * w1;
      if (denominator < 1e-3) continue;  // the contact sits on a fixed node: nothing can give
      const double s = depth / std::max(denominator, 0.25);
      const Eigen::Vector3d shift0 = w0 * s * normal, shift1 = w1 * s * normal;
      positions_.row(i) += shift0.transpose();
      positions_.row(i + 1) += shift1.transpose();
      velocities_.row(i) += shift0.transpose() / settings_.time_step_s;
      velocities_.row(i + 1) += shift1.transpose() / settings_.time_step_s;
    }
  return deepest;
}

std::pair<int, double> TubeRod::SegmentAt(double s_m) const {
  const auto& sc = material_coordinates_;
  const double s = std::clamp(s_m, sc.front(), sc.back());
  auto upper = std::upper_bound(sc.begin(), sc.end(), s);
  int i = static_cast<int>(upper - sc.begin()) - 1;
  i = std::clamp(i, 0, num_nodes() - 2);
  const double span = sc[static_cast<std::size_t>(i) + 1] - sc[static_cast<std::size_t>(i)];
  return {i, std::clamp((s - sc[static_cast<std::size_t>(i)]) / span, 0.0, 1.0)};
}

Eigen::Vector3d TubeRod::PositionAt(double s_m) const {
  const auto [i, f] = SegmentAt(s_m);
  return ((1.0 - f) * positions_.row(i) + f * positions_.row(i + 1)).transpose();
}

double TubeRod::StretchEnergy_J() const {
  double energy = 0.0;
  for (int i = 0; i + 1 < num_nodes(); ++i) {
    const double strain_length =
        (positions_.row(i + 1) - positions_.row(i)).norm() - rest_lengths_[static_cast<std::size_t>(i)];
    energy += 0.5 * stretch_weights_[static_cast<std::size_t>(i)] * strain_length * strain_length;
  }
  return energy;
}

double TubeRod::BendingEnergy_J() const {
  double energy = 0.0;
  for (int i = 1; i + 1 < num_nodes(); ++i) {
    const double l0 = rest_lengths_[static_cast<std::size_t>(i - 1)], l1 = rest_lengths_[static_cast<std::size_t>(i)];
    const Eigen::Vector3d v =
        ((positions_.row(i + 1) - positions_.row(i)) / l1 - (positions_.row(i) - positions_.row(i - 1)) / l0)
            .transpose();
    energy += 0.5 * bending_weights_[static_cast<std::size_t>(i)] * (v - BendingTarget(i, positions_)).squaredNorm();
  }
  return energy;
}

double TubeRod::KineticEnergy_J() const {
  double energy = 0.0;
  for (int i = 0; i < num_nodes(); ++i)
    energy += 0.5 * masses_[static_cast<std::size_t>(i)] * velocities_.row(i).squaredNorm();
  return energy;
}

double TubeRod::GravityPotential_J() const {
  double energy = 0.0;
  for (int i = 0; i < num_nodes(); ++i)
    energy -= masses_[static_cast<std::size_t>(i)] * positions_.row(i).dot(settings_.gravity_m_per_s2.transpose());
  return energy;
}

double TubeRod::CouplingEnergy_J() const {
  double energy = 0.0;
  for (int i = 0; i < num_nodes(); ++i)
    if (holds_[static_cast<std::size_t>(i)] == NodeHold::kCoupled)
      energy +=
          0.5 * settings_.coupling_stiffness_N_per_m * (positions_.row(i) - coupling_targets_.row(i)).squaredNorm();
  return energy;
}

}  // namespace vesica::physics::calot
