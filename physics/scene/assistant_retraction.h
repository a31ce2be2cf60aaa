#pragma once
// The assistant's fixed retraction of the gallbladder's fundus (issue 30): the fundus's nodes
// near the grasp point are held by stiff springs to targets displaced from their rest positions
// (cranially over the liver's edge). Treated like the connective tissue: the force at the start
// of the step comes in as an external force, the stiffness and damping go into the gallbladder's
// implicit system, so the stiff hold is stable on the light fundus nodes.

#include <Eigen/Core>
#include <vector>

#include "physics/mesh/tetrahedral_mesh.h"

namespace vesica::physics {

struct AssistantRetractionSettings {
  bool enabled = false;
  Eigen::Vector3d grasp_point_m = Eigen::Vector3d::Zero();   ///< where the assistant's jaws hold the fundus
  double radius_m = 0.01;                                    ///< nodes within this of grasp_point_m are held, > 0
  Eigen::Vector3d displacement_m = Eigen::Vector3d::Zero();  ///< targets = rest positions + this
  double stiffness_N_per_m = 50.0;                           ///< per held node, > 0
  double damping_Ns_per_m = 0.05;                            ///< per held node, >= 0
};

struct AssistantRetraction {
  std::vector<int> nodes;  ///< held volume nodes
  Vertices targets_m;      ///< one row per held node
  double stiffness_N_per_m = 0;
  double damping_Ns_per_m = 0;
  bool empty() const { return nodes.empty(); }
};

/// The held nodes of `rest_mesh` and their targets; empty when !settings.enabled. Throws
/// std::invalid_argument naming the field for a bad setting or when no node lies within the
/// radius.
AssistantRetraction MakeAssistantRetraction(const TetrahedralMesh& rest_mesh,
                                            const AssistantRetractionSettings& settings);

/// Adds the hold's stiffness and damping to the per-dof attachment vectors (3n each).
void AddRetractionStiffness(const AssistantRetraction& retraction, Eigen::VectorXd& stiffness_N_per_m,
                            Eigen::VectorXd& damping_Ns_per_m);

/// Adds the hold's forces k (target - x) - c v on the held nodes to `force_N` (3n).
void AddRetractionForces(const AssistantRetraction& retraction, const Vertices& positions_m,
                         const Eigen::VectorXd& velocity_m_per_s, Eigen::VectorXd& force_N);

/// Potential energy of the hold, J.
double RetractionEnergy(const AssistantRetraction& retraction, const Vertices& positions_m);

}  // namespace vesica::physics
