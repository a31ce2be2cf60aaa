#pragma once
// Springs from a FEM body to anchors outside it (connective tissue to the liver), lumped per dof.
// Their forces at the start of a step come in as external forces; what the body keeps is their
// stiffness and damping, so the step treats the increment implicitly (stiff tissue on light
// nodes: k = 20 N/m on 4e-5 kg is omega h = 3.5 at h = 5 ms, unstable when applied explicitly).

#include <Eigen/Core>
#include <string>

namespace vesica::physics {

struct AttachmentSprings {
  Eigen::VectorXd stiffness_N_per_m;  ///< 3n, >= 0
  Eigen::VectorXd damping_Ns_per_m;   ///< 3n, >= 0
  bool any = false;                   ///< some entry is non-zero
};

/// Checks sizes (3n each) and entries (finite, >= 0); throws FemError naming the body, the node
/// and the axis. Returns the springs ready for the step.
AttachmentSprings MakeAttachmentSprings(const std::string& body_name, int num_nodes,
                                        const Eigen::VectorXd& stiffness_N_per_m,
                                        const Eigen::VectorXd& damping_Ns_per_m);

}  // namespace vesica::physics
