#pragma once
// The coupled cholecystectomy scene: BEM liver, FEM gallbladder, connective-tissue springs, two
// instruments colliding by rays, grasping and pushing through Lagrange-multiplier constraints.
// One Step() reads as docs/architecture.md's "One physics step" (STYLE.md 3):
//   1. instrument poses -> tool points
//   2. spring forces at the current state (explicit on the stiff liver, implicit stiffness on the
//      gallbladder through FemBody attachments)
//   3. free motion: gallbladder implicit step, liver quasi-static capacitance solve
//   4. ray collision of each tool against the free surfaces (Bullet BVH refitted)
//   5. grasp / slip / release state machine
//   6. constraint solve (W + W_soft) lambda + delta = 0 with W = J C J^T from both bodies
//   7. correction: each body moves by C J^T lambda
//   8. publish per-instrument haptic frames; report what the hook touches (for fx)
// Cautery itself lives in fx (which may not be included here): the caller cuts springs.
// Deterministic: the same commands give bit-identical states on the same binary.

#include <array>
#include <memory>
#include <string>
#include <vector>

#include "physics/bem/capacitance_solver.h"
#include "physics/collision/surface_ray_caster.h"
#include "physics/fem/fem_body.h"
#include "physics/grasp/grasp_state_machine.h"
#include "physics/instrument/instrument_pose.h"
#include "physics/scene/constraint_solver.h"
#include "physics/scene/dissection_model.h"
#include "physics/scene/fem_rest_compliance.h"
#include "physics/scene/grasp_jaw.h"
#include "physics/scene/haptic_contact_frame.h"
#include "physics/scene/jaw_press_subgrid.h"

namespace vesica::physics {

enum class TouchedSurface { kNone, kLiver, kGallbladder };

/// What an instrument's tip touches after the step.
struct ToolTouch {
  TouchedSurface surface = TouchedSurface::kNone;
  int triangle = -1;  ///< liver surface triangle or gallbladder boundary triangle
  Eigen::Vector3d weights = Eigen::Vector3d::Constant(1.0 / 3.0);
  Eigen::Vector3d p_Tip_W = Eigen::Vector3d::Zero();
  double gap_m = 0;                    ///< signed distance tip - surface along the normal (< 0: pressing)
  std::vector<int> membrane_elements;  ///< membrane triangles within the touch radius of the tip
};

/// Wall time of each stage of the last step, microseconds (not part of the state).
struct StageTimes {
  double springs_us = 0, gallbladder_us = 0, liver_us = 0, collision_us = 0, grasp_us = 0, constraints_us = 0,
         correction_us = 0, total_us = 0;
};

struct DissectionStepReport {
  bool gallbladder_accepted = true;
  std::string rejection_reason;              ///< why the gallbladder step was rolled back
  int gallbladder_solver_iterations = 0;     ///< PCG iterations of the gallbladder step (0: direct)
  double gallbladder_relative_residual = 0;  ///< its PCG residual |b - S du| / |b| (0: direct)
  int constraint_rows = 0;
  int obstacle_contacts = 0;  ///< gallbladder nodes pushed by a static obstacle or the liver (lambda > 0)
  ConstraintSolution constraints;
  GraspEvents grasp;
  std::array<ToolTouch, 2> touches;
  std::array<Eigen::Vector3d, 2> tool_force_N{Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
  StageTimes times;
};

class DissectionScene {
 public:
  explicit DissectionScene(std::shared_ptr<const DissectionModel> model);
  ~DissectionScene();
  DissectionScene(const DissectionScene&) = delete;
  DissectionScene& operator=(const DissectionScene&) = delete;

  /// One physics step with the instruments at `poses` ([0] grasper, [1] hook). Throws
  /// std::invalid_argument (state unchanged) for a non-finite or negative-insertion pose.
  DissectionStepReport Step(const std::array<InstrumentPose, 2>& poses);

  /// Removes spring `index` (its membrane burnt away); the gallbladder's attachments follow.
  void CutSpring(int index);

  /// A body outside the scene that pulls on gallbladder nodes (Calot's tubes on the neck). From
  /// the next step on, the force of SetOutsideLoadForce is spread evenly over `nodes`, and
  /// `stiffness_N_per_m` (how stiff that body is to the nodes' common motion, >= 0) enters the
  /// gallbladder's implicit step as the springs' stiffness does, so that a force computed a step
  /// behind the motion stays stable. A changed stiffness refactorises in the background, as a cut
  /// spring does. Throws std::invalid_argument (nothing changed) for a node out of range or a
  /// negative or non-finite stiffness.
  void SetOutsideLoad(const std::vector<int>& nodes, double stiffness_N_per_m);
  /// The outside body's force on the nodes of SetOutsideLoad, N, in total. Throws
  /// std::invalid_argument for a non-finite force or when no nodes were set.
  void SetOutsideLoadForce(const Eigen::Vector3d& force_N);

  const DissectionModel& model() const { return *model_; }
  double time_s() const { return time_s_; }
  long steps() const { return steps_; }
  const ConnectiveTissue& tissue() const { return tissue_; }
  const GraspStateMachine& grasp() const { return grasp_; }
  /// The footprint a grasp holds and its subgrid compliance (DissectionSettings::grasp_holds_jaw_footprint).
  const GraspJaw& grasp_jaw() const { return grasp_jaw_; }
  bool gallbladder_free() const { return tissue_.num_alive() == 0; }

  /// Current liver surface vertices (#V x 3) and gallbladder boundary vertices (boundary numbering).
  const Vertices& liver_positions() const { return liver_current_.vertices; }
  Vertices gallbladder_surface_positions() const;
  const FemBody& gallbladder() const { return gallbladder_; }
  /// Membrane points: 2s gallbladder end, 2s+1 liver end of spring s (TissueMembrane numbering).
  Vertices membrane_points() const;
  /// Tool tip of instrument i at the last step.
  const Eigen::Vector3d& tool_tip(int i) const { return tips_.at(static_cast<size_t>(i)); }
  const HapticContactFrame& haptic_frame(int i) const { return frames_.at(static_cast<size_t>(i)); }
  /// Liver kinetic energy is not modelled (quasi-static BEM); this is the gallbladder's kinetic +
  /// elastic energy plus the springs' and the assistant's hold's potential energy, J.
  double Energy() const;

 private:
  struct Row;
  struct JawRows;
  // The springs alive now -> the gallbladder's implicit system and the constraint compliance
  // (on a worker thread when `in_background`, adopted compliance_adopt_steps later).
  void UpdateAttachments(bool in_background);
  Eigen::Matrix3d BlockCompliance(const Row& a, const Row& b);
  // The closed jaws' footprint where the grasper presses the gallbladder at `hit` (rest frame),
  // with the press's subgrid compliance along the hit's normal; null where none can be formed.
  std::shared_ptr<const JawRows> PressingJaw(const SurfaceHit& hit, const Eigen::Vector3d& shaft);
  // The gallbladder volume nodes and weights a row's tissue point is the weighted sum of.
  void GallbladderPoints(const Row& r, std::vector<std::pair<int, double>>& out) const;
  // One-sided rows for the gallbladder's surface nodes (at their free positions) within the margin
  // of a static obstacle or of the liver's free surface, each pressed one followed by its two
  // friction rows (which hold it at its position at the step's start).
  std::vector<Row> ObstacleRows(const Vertices& gb_start, const Vertices& gb_free, const Vertices& liver_free) const;
  // W among rows[first...] (the obstacle rows, grouped by node), both triangles.
  void AddObstacleDelassus(const std::vector<Row>& rows, Eigen::Index first, ConstraintProblem& problem);

  std::shared_ptr<const DissectionModel> model_;
  FemBody gallbladder_;
  FemRestCompliance gallbladder_compliance_;
  BemCapacitanceSolver liver_solver_;
  ConnectiveTissue tissue_;
  GraspStateMachine grasp_;
  GraspJaw grasp_jaw_;             // the footprint a grasp holds and its subgrid compliance
  JawPressSubgrid press_subgrid_;  // the closed jaws' press on the gallbladder, per surface vertex
  // The grasp's load columns C J^T, for the grasp taken at grasp_jaw_take_step_ and the
  // compliance's factorisation it was solved with.
  Eigen::Matrix<double, Eigen::Dynamic, 3> grasp_jaw_columns_;
  long grasp_jaw_take_step_ = -1, grasp_jaw_columns_take_ = -1;
  int grasp_jaw_columns_factorization_ = -1;
  SurfaceRayCaster caster_;
  int liver_surface_id_ = -1, gallbladder_surface_id_ = -1;
  TetrahedralMesh gallbladder_current_;  // rest topology, current vertices
  TriangleMesh liver_current_;
  Vertices liver_velocity_;
  BemSolution liver_solution_;
  std::array<Eigen::Vector3d, 2> tips_{Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
  std::array<HapticContactFrame, 2> frames_;
  std::vector<double> grasp_point_forces_;  // |lambda| per grasped point, last step
  // The obstacle rows' forces of the last step per gallbladder node (contact, friction 1 and 2),
  // the next solve's warm start; obstacle_lambda_nodes_: the nodes that had them.
  std::vector<std::array<double, 3>> obstacle_lambda_;
  std::vector<int> obstacle_lambda_nodes_;
  std::vector<int> outside_load_nodes_;
  double outside_load_stiffness_N_per_m_ = 0;
  Eigen::Vector3d outside_load_force_N_ = Eigen::Vector3d::Zero();
  bool attachments_changed_ = false;
  int steps_since_compliance_ = 0;
  long compliance_adopt_step_ = -1;  // step at which the compliance begun on a worker is adopted; -1: none
  double time_s_ = 0;
  long steps_ = 0;
};

}  // namespace vesica::physics
