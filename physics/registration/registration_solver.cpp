#include "physics/registration/registration_solver.h"

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "physics/mesh/mesh_topology.h"
#include "physics/scene/fem_rest_compliance.h"

namespace vesica::physics {

namespace {
void CheckSettings(const RegistrationSettings& s) {
  if (!(s.min_normal_cosine >= -1.0 && s.min_normal_cosine <= 1.0))
    throw std::invalid_argument("RegistrationSettings: min_normal_cosine must be in [-1, 1]");
  if (!(s.max_pairing_distance_m > 0.0) || !std::isfinite(s.max_pairing_distance_m))
    throw std::invalid_argument("RegistrationSettings: max_pairing_distance_m must be finite and > 0");
  if (!(s.soft_compliance_m_per_N >= 0.0) || !std::isfinite(s.soft_compliance_m_per_N))
    throw std::invalid_argument("RegistrationSettings: soft_compliance_m_per_N must be finite and >= 0");
}

// One constraint row in the body's rest frame: m = R^T n, so that n^T (R C0 R^T) n' = m^T C0 m'.
struct Row {
  const SurfacePairing* pairing = nullptr;
  Eigen::Vector3d rest_normal;
};
}  // namespace

void CheckControlPoint(const ControlPoint& p, int index) {
  const std::string where = "control point " + std::to_string(index);
  if (!p.p_W.allFinite() || !p.inward_normal_W.allFinite() || !std::isfinite(p.confidence))
    throw std::invalid_argument(where + ": not finite");
  if (!(p.inward_normal_W.norm() > 1e-9)) throw std::invalid_argument(where + ": normal of zero length");
  if (!(p.confidence > 0.0 && p.confidence <= 1.0))
    throw std::invalid_argument(where + ": confidence " + std::to_string(p.confidence) + " outside (0, 1]");
}

Eigen::Matrix3d BestFitRotation(const Vertices& rest, const Vertices& current, const Eigen::VectorXd& mass) {
  Eigen::Vector3d rest_centre = Eigen::Vector3d::Zero(), current_centre = Eigen::Vector3d::Zero();
  double total = 0.0;
  for (Eigen::Index i = 0; i < rest.rows(); ++i) {
    const double m = mass[3 * i];
    rest_centre += m * rest.row(i).transpose();
    current_centre += m * current.row(i).transpose();
    total += m;
  }
  rest_centre /= total;
  current_centre /= total;
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (Eigen::Index i = 0; i < rest.rows(); ++i)
    covariance += mass[3 * i] * (current.row(i).transpose() - current_centre) *
                  (rest.row(i).transpose() - rest_centre).transpose();
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(covariance, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d d = Eigen::Matrix3d::Identity();
  d(2, 2) = (svd.matrixU() * svd.matrixV().transpose()).determinant() < 0.0 ? -1.0 : 1.0;
  return svd.matrixU() * d * svd.matrixV().transpose();
}

RegistrationSolver::RegistrationSolver(std::shared_ptr<const FemModel> model, const RegistrationSettings& settings)
    : model_(std::move(model)),
      settings_(settings),
      body_(model_),
      compliance_(std::make_unique<FemRestCompliance>(model_)),
      surface_(ExtractBoundary(model_->rest_mesh)) {
  CheckSettings(settings_);
}

RegistrationSolver::~RegistrationSolver() = default;

Vertices RegistrationSolver::Displacement() const { return body_.CurrentPositions() - model_->rest_mesh.vertices; }

RegistrationStepReport RegistrationSolver::Step(const std::vector<ControlPoint>& points) {
  for (size_t i = 0; i < points.size(); ++i) CheckControlPoint(points[i], static_cast<int>(i));
  RegistrationStepReport report;

  // 1. Free motion: the corotational body's implicit step (eq. 3 with lambda = 0).
  report.fem = body_.Step();
  const Vertices x = body_.CurrentPositions();

  // 2. Pairing (sections 3.3-3.4) on the free positions.
  const PairingOptions options{settings_.check_normals, settings_.min_normal_cosine, settings_.max_pairing_distance_m};
  pairings_.clear();
  std::vector<const ControlPoint*> paired;
  const SurfaceSnapshot snapshot(surface_, x);
  for (const ControlPoint& p : points) {
    if (auto pairing = PairControlPoint(snapshot, p, options)) {
      pairings_.push_back(*pairing);
      paired.push_back(&p);
    } else {
      ++report.unpaired_points;
    }
  }
  const Eigen::Index m = static_cast<Eigen::Index>(pairings_.size());
  report.paired_points = static_cast<int>(m);

  // 3. Schur complement: W = J (R C0 R^T) J^T along the normals, W_soft from the confidences.
  rotation_ = BestFitRotation(model_->rest_mesh.vertices, x, model_->lumped_mass_kg);
  std::vector<Row> rows(static_cast<size_t>(m));
  ConstraintProblem problem;
  problem.delassus.setZero(m, m);
  problem.soft_compliance.resize(m);
  problem.gap.resize(m);
  problem.kinds.assign(static_cast<size_t>(m), ConstraintKind::kBilateral);
  for (Eigen::Index a = 0; a < m; ++a) {
    const SurfacePairing& s = pairings_[static_cast<size_t>(a)];
    rows[static_cast<size_t>(a)] = {&s, rotation_.transpose() * s.inward_normal_W};
    // delta = n . (q_s - q_i): a force +n lambda on q_s changes it by W lambda.
    problem.gap[a] = s.inward_normal_W.dot(s.p_Surface_W - paired[static_cast<size_t>(a)]->p_W);
    const double c = paired[static_cast<size_t>(a)]->confidence;
    problem.soft_compliance[a] = settings_.soft_compliance_m_per_N * (1.0 - c) / c;
  }
  report.max_gap_before_m = m > 0 ? problem.gap.cwiseAbs().maxCoeff() : 0.0;
  for (Eigen::Index b = 0; b < m; ++b) {
    const Row& rb = rows[static_cast<size_t>(b)];
    for (int j = 0; j < 3; ++j) {
      const double wj = rb.pairing->weights[j];
      if (wj == 0.0) continue;
      const auto& columns = compliance_->NodeColumns(rb.pairing->nodes[static_cast<size_t>(j)]);
      const Eigen::Vector3d column_b = wj * rb.rest_normal;
      for (Eigen::Index a = 0; a <= b; ++a) {
        const Row& ra = rows[static_cast<size_t>(a)];
        double w = 0.0;
        for (int i = 0; i < 3; ++i) {
          const double wi = ra.pairing->weights[i];
          if (wi == 0.0) continue;
          w +=
              wi * ra.rest_normal.dot(columns.block<3, 3>(3 * ra.pairing->nodes[static_cast<size_t>(i)], 0) * column_b);
        }
        problem.delassus(a, b) += w;
      }
    }
  }
  problem.delassus.triangularView<Eigen::StrictlyLower>() = problem.delassus.transpose();
  report.constraints = SolveConstraints(problem);
  const Eigen::VectorXd& lambda = report.constraints.lambda;

  // 4. Correction: du = R C0 R^T J^T n lambda, applied per node in the world frame.
  Eigen::VectorXd du_rest = Eigen::VectorXd::Zero(model_->num_dofs());
  for (Eigen::Index a = 0; a < m; ++a) {
    const Row& r = rows[static_cast<size_t>(a)];
    for (int j = 0; j < 3; ++j) {
      const double wj = r.pairing->weights[j];
      if (wj == 0.0 || lambda[a] == 0.0) continue;
      du_rest.noalias() +=
          compliance_->NodeColumns(r.pairing->nodes[static_cast<size_t>(j)]) * (wj * lambda[a] * r.rest_normal);
    }
  }
  Eigen::VectorXd du(model_->num_dofs());
  for (int v = 0; v < model_->num_nodes(); ++v) du.segment<3>(3 * v) = rotation_ * du_rest.segment<3>(3 * v);
  const FemState& state = body_.state();
  const Eigen::VectorXd u = state.displacement_m + du;
  const double h = model_->settings.time_step_s;
  body_.SetState(
      u, settings_.quasi_static ? Eigen::VectorXd::Zero(u.size()) : Eigen::VectorXd(state.velocity_m_per_s + du / h));

  // 5. What is left of each gap (the same pairing, at the corrected positions).
  double sum = 0.0;
  for (Eigen::Index a = 0; a < m; ++a) {
    const SurfacePairing& s = pairings_[static_cast<size_t>(a)];
    Eigen::Vector3d q_s = Eigen::Vector3d::Zero();
    for (int k = 0; k < 3; ++k) {
      const int node = s.nodes[static_cast<size_t>(k)];
      q_s += s.weights[k] * (model_->rest_mesh.vertices.row(node).transpose() + u.segment<3>(3 * node));
    }
    const double gap = std::abs(s.inward_normal_W.dot(q_s - paired[static_cast<size_t>(a)]->p_W));
    report.max_gap_after_m = std::max(report.max_gap_after_m, gap);
    sum += gap;
  }
  report.mean_gap_after_m = m > 0 ? sum / static_cast<double>(m) : 0.0;
  return report;
}

}  // namespace vesica::physics
