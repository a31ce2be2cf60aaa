#include "fx/cautery_contact.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "fx/input_checks.h"

namespace vesica::fx {

const char* ToString(CauterySurface surface) {
  switch (surface) {
    case CauterySurface::kNone:
      return "none";
    case CauterySurface::kLiver:
      return "liver";
    case CauterySurface::kGallbladder:
      return "gallbladder";
    case CauterySurface::kMembrane:
      return "membrane";
  }
  return "unknown";
}

void ValidateCauteryContact(const CauteryContact& contact) {
  const std::string owner = "CauteryContact";
  CheckNonNegative(owner, "dt_s", contact.dt_s);
  CheckFinite(owner, "p_WTip_W", contact.p_WTip_W);
  if (contact.surface == CauterySurface::kNone) return;
  CheckFinite(owner, "barycentric", contact.barycentric);
  const Eigen::Vector3d& w = contact.barycentric;
  if (w.minCoeff() < -1e-6 || w.maxCoeff() > 1 + 1e-6 || std::abs(w.sum() - 1) > 1e-6) {
    std::ostringstream msg;
    msg << owner << ": barycentric (" << w.x() << ", " << w.y() << ", " << w.z() << ") must lie in [0, 1] and sum to 1";
    throw std::invalid_argument(msg.str());
  }
}

}  // namespace vesica::fx
