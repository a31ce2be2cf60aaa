#include "fx/cautery_effects.h"

#include <stdexcept>
#include <string>

#include "fx/input_checks.h"

namespace vesica::fx {

namespace {

MembraneRemoval MakeMembrane(const CauterySurfaces& surfaces, const MembraneParams& params) {
  if (static_cast<int>(surfaces.membrane_element_springs.size()) != surfaces.membrane.num_triangles()) {
    throw std::invalid_argument("CauteryEffects: membrane_element_springs has " +
                                std::to_string(surfaces.membrane_element_springs.size()) + " entries, membrane has " +
                                std::to_string(surfaces.membrane.num_triangles()) + " triangles");
  }
  return MembraneRemoval(surfaces.membrane_element_springs, surfaces.num_springs, params);
}

}  // namespace

CauteryEffects::CauteryEffects(const CauterySurfaces& surfaces, const CauteryParams& params)
    : liver_("liver", surfaces.liver, params.liver_burn),
      gallbladder_("gallbladder", surfaces.gallbladder, params.gallbladder_burn),
      membrane_burn_("membrane", surfaces.membrane, params.membrane_burn),
      membrane_(MakeMembrane(surfaces, params.membrane)),
      smoke_(params.smoke) {}

BurnMap& CauteryEffects::MapOf(CauterySurface surface) {
  switch (surface) {
    case CauterySurface::kLiver:
      return liver_;
    case CauterySurface::kGallbladder:
      return gallbladder_;
    case CauterySurface::kMembrane:
      return membrane_burn_;
    case CauterySurface::kNone:
      break;
  }
  throw std::logic_error("CauteryEffects: no burn map for surface 'none'");
}

void CauteryEffects::Step(const CauteryContact& contact) {
  // Every check before any change, so a rejected contact leaves the state as it was.
  ValidateCauteryContact(contact);
  if (contact.surface != CauterySurface::kNone) {
    CheckIndex(std::string("CauteryEffects: ") + ToString(contact.surface) + " surface", "element", contact.element,
               MapOf(contact.surface).num_elements());
  }
  for (const int e : contact.more_membrane_elements) {
    if (contact.surface != CauterySurface::kMembrane)
      throw std::invalid_argument(std::string("CauteryEffects: more_membrane_elements given for a contact with the ") +
                                  ToString(contact.surface) + " surface");
    CheckIndex("CauteryEffects: membrane surface", "more_membrane_elements", e, membrane_burn_.num_elements());
  }
  time_s_ += contact.dt_s;
  if (contact.active()) {
    MapOf(contact.surface).Burn(contact.element, contact.dt_s, time_s_);
    if (contact.surface == CauterySurface::kMembrane) {
      membrane_.Touch(contact.element, contact.dt_s, time_s_);
      for (const int e : contact.more_membrane_elements) {
        membrane_burn_.Burn(e, contact.dt_s, time_s_);
        membrane_.Touch(e, contact.dt_s, time_s_);
      }
    }
  }
  smoke_.Update(contact.dt_s, contact.active(), contact.p_WTip_W);
}

double CauteryEffects::damaged_area_m2() const { return liver_.damaged_area_m2() + gallbladder_.damaged_area_m2(); }

}  // namespace vesica::fx
