#pragma once
// Compliance of a FEM body for the constraint solver, from the system matrix at rest
// (S0 = c_M M + c_D D + K0 + attachments; C = S0^-1), factorised once with CHOLMOD and solved
// column by column only for the nodes constraints touch, cached until the attachments change.
// This is SOFA's precomputed constraint correction made lazy: exact for a linear body, the
// rest-shape approximation for a corotational one (its W is then what the body would feel
// without its current rotation; the correction is re-linearised every step, so errors do not
// accumulate). Keeps the per-step cost to a few dense 3x3 blocks instead of 3m sparse solves.

#include <Eigen/Core>
#include <memory>
#include <utility>
#include <vector>

#include "physics/fem/cholmod_solver.h"
#include "physics/fem/fem_model.h"

namespace vesica::physics {

class FemRestCompliance {
 public:
  explicit FemRestCompliance(std::shared_ptr<const FemModel> model);
  ~FemRestCompliance();

  /// Per-dof attachment stiffness and damping (as FemBody::SetAttachmentStiffness); factorises S0
  /// with them now and drops the cached columns. Sizes 3n, entries >= 0. Throws FemError if S0
  /// is not positive definite.
  void SetAttachments(const Eigen::VectorXd& stiffness_N_per_m, const Eigen::VectorXd& damping_Ns_per_m);

  /// SetAttachments without the wait: factorises S0 with the new attachments on a worker thread
  /// while NodeColumns goes on answering from the current factor until AdoptAttachments(). A
  /// Begin while one is pending first adopts that one. Throws as SetAttachments for bad sizes.
  /// `shared`, when valid, is the same S0's factor already being computed elsewhere (the FEM body's
  /// FemBody::PendingRestFactor() for the same attachments): the worker waits for it instead of
  /// factorising S0 a second time.
  void BeginAttachments(const Eigen::VectorXd& stiffness_N_per_m, const Eigen::VectorXd& damping_Ns_per_m,
                        RestFactorFuture shared = {});
  /// Waits for the factorisation BeginAttachments started (usually long done) and answers from it
  /// from now on; cached columns start over. Nothing to do when none is pending. Throws FemError
  /// if that S0 is not positive definite (the current factor then stays).
  void AdoptAttachments();
  bool attachments_pending() const;

  /// The 3n x 3 block of C for a unit force at `node` (m/N): displacement increments of every
  /// dof. Factorises on first use after a change. Throws FemError if S0 is not positive definite.
  const Eigen::Matrix<double, Eigen::Dynamic, 3>& NodeColumns(int node);

  /// The 3n x 3 block of C for unit forces spread over `points` (node, weight): C J^T for the
  /// rows J of a load on those nodes, in one solve with three right-hand sides (instead of one per
  /// node). Not cached: the caller keeps it while factorizations() stays. Throws FemError as
  /// NodeColumns, and for a node out of range.
  Eigen::Matrix<double, Eigen::Dynamic, 3> LoadColumns(const std::vector<std::pair<int, double>>& points);

  int factorizations() const { return factorizations_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  int factorizations_ = 0;
};

}  // namespace vesica::physics
