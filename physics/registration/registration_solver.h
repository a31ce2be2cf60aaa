#pragma once
// Constraint-based non-rigid registration (Courtecuisse et al., seed sections 3.2-3.4): each step
// the corotational FEM body takes a free implicit step, the control points are paired with its
// surface, and one sliding constraint per point,
//   delta_i = n_i . (J_i x - q_i)                                          (eq. 5)
// is solved with the Schur complement (W + W_soft) lambda + delta = 0, W = J C J^T (eqs. 1-4, 6),
// by the scene's constraint solver; the body then moves by C J^T lambda. C is the body's rest
// compliance (FemRestCompliance: S0^-1, one CHOLMOD factor, columns cached per node) turned by the
// body's current best-fit rotation R, C ~ R C0 R^T (warped compliance), so that a liver that
// re-orients keeps the right W.

#include <Eigen/Core>
#include <memory>
#include <vector>

#include "physics/fem/fem_body.h"
#include "physics/fem/fem_model.h"
#include "physics/registration/control_point.h"
#include "physics/registration/registration_settings.h"
#include "physics/registration/surface_pairing.h"
#include "physics/scene/constraint_solver.h"

namespace vesica::physics {

class FemRestCompliance;

struct RegistrationStepReport {
  StepReport fem;           ///< the free step
  int paired_points = 0;    ///< constraint rows this step
  int unpaired_points = 0;  ///< points with no eligible triangle within reach
  ConstraintSolution constraints;
  double max_gap_before_m = 0.0;  ///< max |delta| after the free step
  double max_gap_after_m = 0.0;   ///< max |delta| after the correction (same pairing)
  double mean_gap_after_m = 0.0;
};

class RegistrationSolver {
 public:
  /// `model`: the organ's FEM model (no fixed nodes needed: the constraints hold it). Throws
  /// std::invalid_argument for bad settings.
  RegistrationSolver(std::shared_ptr<const FemModel> model, const RegistrationSettings& settings);
  ~RegistrationSolver();

  /// One registration step towards `points`. Throws std::invalid_argument for a non-finite point,
  /// a normal of zero length or a confidence outside (0, 1].
  RegistrationStepReport Step(const std::vector<ControlPoint>& points);

  const FemModel& model() const { return *model_; }
  const FemBody& body() const { return body_; }
  const RegistrationSurface& surface() const { return surface_; }
  Vertices CurrentPositions() const { return body_.CurrentPositions(); }
  /// Nodal displacement from the rest mesh, #V by 3, metres.
  Vertices Displacement() const;
  /// Pairings of the last step's points (one per paired point, in order).
  const std::vector<SurfacePairing>& last_pairings() const { return pairings_; }
  /// The rotation R of the warped compliance at the last step.
  const Eigen::Matrix3d& last_rotation() const { return rotation_; }

 private:
  std::shared_ptr<const FemModel> model_;
  RegistrationSettings settings_;
  FemBody body_;
  std::unique_ptr<FemRestCompliance> compliance_;
  RegistrationSurface surface_;
  std::vector<SurfacePairing> pairings_;
  Eigen::Matrix3d rotation_ = Eigen::Matrix3d::Identity();
};

/// Rotation R minimising sum_i m_i |R (X_i - X_c) - (x_i - x_c)|^2 (shape matching, polar part of
/// the mass-weighted covariance); proper (det +1). X, x: #V by 3; mass: 3n lumped (per dof).
Eigen::Matrix3d BestFitRotation(const Vertices& rest_W, const Vertices& current_W,
                                const Eigen::VectorXd& lumped_mass_kg);

/// Throws std::invalid_argument naming the point's index when it is not usable.
void CheckControlPoint(const ControlPoint& point, int index);

}  // namespace vesica::physics
