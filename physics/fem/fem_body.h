#pragma once
// A deformable tetrahedral body advanced by implicit steps: owns its per-step state and solver
// workspace, shares the const FemModel. Used by the scene (gallbladder), needle and registration.

#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "physics/fem/cg_spectrum_estimate.h"
#include "physics/fem/cholmod_solver.h"
#include "physics/fem/fem_model.h"
#include "physics/fem/fem_state.h"
#include "physics/mesh/barycentric.h"

namespace vesica::physics {

struct PassProducts;

struct StepReport {
  bool accepted = false;           ///< false: the state was rolled back (left as before the step)
  int solver_iterations = 0;       ///< PCG iterations (0 for a direct CHOLMOD solve)
  double relative_residual = 0.0;  ///< PCG |b - S du| / |b|; 0 for a direct solve
  bool factorised = false;         ///< this step factorised a system (CHOLMOD): the slow steps
  SpectrumEstimate solver_spectrum;  ///< PCG's estimate of P^-1 S's extreme eigenvalues ({0, 0}: none)
  double energy_J = 0.0;           ///< kinetic + elastic after the step (before it when rejected)
  std::string rejection_reason;    ///< names the body and what went wrong
};

/// Compliance of constrained points: C = S^-1 with S the step's system matrix
/// (M/h^2 + D/h + K for backward Euler), J the 3m x 3n barycentric map of the points.
struct PointCompliance {
  Eigen::MatrixXd response;  ///< C J^T, 3n x 3m: displacement increment per unit point force, m/N
  Eigen::MatrixXd delassus;  ///< W = J C J^T, 3m x 3m, m/N
};

class FemBody {
 public:
  explicit FemBody(std::shared_ptr<const FemModel> model);
  ~FemBody();
  FemBody(FemBody&&) noexcept;
  FemBody& operator=(FemBody&&) noexcept;

  const FemModel& model() const { return *model_; }
  const FemState& state() const { return state_; }

  /// Nodal forces (3n, N) applied during the following steps. Throws FemError on size or NaN.
  void SetExternalForces(const Eigen::VectorXd& force_N);
  /// Replaces u and v (3n each; a is recomputed at the next Newmark step). Throws FemError.
  void SetState(const Eigen::VectorXd& displacement_m, const Eigen::VectorXd& velocity_m_per_s);

  /// Stiffness (N/m) and damping (N s/m) per dof (3n each, >= 0) of springs from this body to anchors
  /// outside it (connective tissue to the liver), lumped onto the nodes (a point with barycentric
  /// weights w on a spring k contributes k*w_i to each of its nodes: diag(w) >= w w^T, so lumping is
  /// stable). They enter the step's system matrix and compliance like K and D do; the springs' forces
  /// at the start of the step still come in through SetExternalForces. Throws FemError on wrong size,
  /// negative or non-finite entries. Zero vectors (the default) change nothing.
  void SetAttachmentStiffness(const Eigen::VectorXd& stiffness_N_per_m, const Eigen::VectorXd& damping_Ns_per_m);
  /// kRotatedFactorPcg with rotated_factor_adopt_steps > 0: the factor of the rest system S0 (c_M M +
  /// c_D D + K0 + the attachments just set) that SetAttachmentStiffness started on a worker thread,
  /// until the step that adopts it; invalid otherwise. Others needing S0^-1 for the same
  /// attachments (the scene's constraint compliance) share it instead of factorising again.
  RestFactorFuture PendingRestFactor() const;

  /// One implicit step of settings.time_step_s. Never lets a non-finite value into the state.
  StepReport Step();

  /// Current vertex positions X + u, #V x 3.
  Vertices CurrentPositions() const;
  double KineticEnergy() const;
  /// Elastic energy at the current displacement (one pass over the elements).
  double ElasticEnergy() const;

  /// Compliance for points bound to tets (weights from barycentric.h). Uses the system matrix of
  /// the last step (assembled at the current state if none yet): exact for linear bodies.
  PointCompliance Compliance(const std::vector<TetLocation>& points);

 private:
  struct Workspace;
  /// The element pass at u: forces, rotations and S (or what stands for it); products: taken in
  /// the same pass (ProductsMatrixFree bodies only).
  void AssembleSystem(const Eigen::VectorXd& u, const PassProducts* products = nullptr);
  /// S = stiffness K_t + the mass and spring terms (AddSystemTerms), for a K_t given whole.
  void SystemValuesFromTangent(const Eigen::VectorXd& tangent, Eigen::VectorXd& system) const;
  /// Adds mass M (+ springs) to values holding stiffness K_t, then makes the Dirichlet rows and
  /// columns the identity's.
  void AddSystemTerms(Eigen::VectorXd& system) const;
  /// The same on the float rows the element pass wrote S's stiffness into (TangentInFloatRows).
  void AddSystemTermsToFloatRows();
  /// S is kept only as the Gauss-Seidel sweeps' float rows, written by the element pass (the
  /// shipped rotated-factor solver: matrix-free products, lumped mass, a vectorised pass); no
  /// double S is assembled.
  bool TangentInFloatRows() const;
  void UpdateNodeRotations();
  bool SolveSystem(const Eigen::VectorXd& rhs, Eigen::VectorXd& du, double tolerance, int max_iterations,
                   StepReport* report);
  /// y = D x (Rayleigh); tangent_x: K_t x when the caller has it (from the element pass).
  void DampingTimes(const Eigen::VectorXd& x, Eigen::VectorXd& y, const Eigen::VectorXd* tangent_x = nullptr) const;
  /// The tangent is applied element by element and never assembled (TangentIsMatrixFree).
  bool MatrixFree() const;
  /// Products with K_t and S element by element, S assembled or not (ProductsAreMatrixFree).
  bool ProductsMatrixFree() const;
  /// y = K_t x, element by element or from S (then 0 on the fixed dofs, and x's fixed entries
  /// taken as 0).
  void TangentTimes(const Eigen::VectorXd& x, Eigen::VectorXd& y) const;
  /// y = S x (the system matrix SystemValuesFromTangent builds) from products, for ProductsMatrixFree().
  void SystemTimes(const Eigen::VectorXd& x, Eigen::VectorXd& y) const;
  /// The same from y = K_t (x with its fixed entries taken as 0), overwritten with S x.
  void SystemTimesFromTangentProduct(const Eigen::VectorXd& x, Eigen::VectorXd& y) const;
  /// du . K_t du for the step's energy check: from S du, which kRotatedFactorPcg's solve leaves
  /// (S du = b - r), minus the mass and spring terms, when the mass is lumped; else one product.
  double TangentQuadraticForm(const Eigen::VectorXd& du) const;

  std::shared_ptr<const FemModel> model_;
  FemState state_;
  std::unique_ptr<Workspace> work_;
};

}  // namespace vesica::physics
