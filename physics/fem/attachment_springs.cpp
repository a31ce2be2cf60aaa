#include "physics/fem/attachment_springs.h"

#include <cmath>
#include <sstream>

#include "physics/fem/fem_error.h"

namespace vesica::physics {

namespace {
void Check(const std::string& body, int num_nodes, const Eigen::VectorXd& x, const char* what) {
  if (x.size() != 3 * num_nodes) {
    std::ostringstream os;
    os << body << ": attachment " << what << " has " << x.size() << " entries, expected 3 x " << num_nodes;
    throw FemError(os.str());
  }
  for (Eigen::Index i = 0; i < x.size(); ++i)
    if (!std::isfinite(x[i]) || x[i] < 0.0) {
      std::ostringstream os;
      os << body << ": attachment " << what << " of node " << i / 3 << " (axis " << i % 3 << ", dof " << i << ") is "
         << x[i] << ": must be finite and >= 0";
      throw FemError(os.str());
    }
}
}  // namespace

AttachmentSprings MakeAttachmentSprings(const std::string& body_name, int num_nodes, const Eigen::VectorXd& stiffness,
                                        const Eigen::VectorXd& damping) {
  Check(body_name, num_nodes, stiffness, "stiffness");
  Check(body_name, num_nodes, damping, "damping");
  AttachmentSprings s;
  s.stiffness_N_per_m = stiffness;
  s.damping_Ns_per_m = damping;
  s.any = (stiffness.array() != 0.0).any() || (damping.array() != 0.0).any();
  return s;
}

}  // namespace vesica::physics
