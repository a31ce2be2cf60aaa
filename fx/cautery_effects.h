#pragma once
// All cautery effects of the scene behind one call per physics step (docs/architecture.md step 3):
// burn maps of liver, gallbladder and membrane, damage accounting, membrane removal and smoke.
// Owns its simulation clock (sum of the contacts' dt), so a replayed input stream gives the
// same state bit for bit.

#include <vector>

#include "fx/burn_map.h"
#include "fx/cautery_contact.h"
#include "fx/membrane_removal.h"
#include "fx/smoke_emitter.h"
#include "physics/mesh/triangle_mesh.h"

namespace vesica::fx {

/// The surfaces cautery acts on; read once, fx keeps its own copies of what it needs.
struct CauterySurfaces {
  physics::TriangleMesh liver;
  physics::TriangleMesh gallbladder;                       ///< the FEM mesh's boundary surface
  physics::TriangleMesh membrane;                          ///< one triangle per membrane element
  std::vector<std::vector<int>> membrane_element_springs;  ///< #membrane.F: springs of each element
  int num_springs = 0;
};

struct CauteryParams {
  BurnParams liver_burn;
  BurnParams gallbladder_burn;
  BurnParams membrane_burn{
      .rate_per_s = 1.0, .spread_radius_m = 0.002, .damage_threshold = 1.0, .records_damage = false};
  MembraneParams membrane;
  SmokeParams smoke;
};

class CauteryEffects {
 public:
  CauteryEffects(const CauterySurfaces& surfaces, const CauteryParams& params);

  /// One physics step. Throws std::invalid_argument (state unchanged) for a bad contact:
  /// negative/non-finite dt, non-finite tip, bad barycentric, or element out of range.
  void Step(const CauteryContact& contact);

  double time_s() const { return time_s_; }
  const BurnMap& liver_burn() const { return liver_; }
  const BurnMap& gallbladder_burn() const { return gallbladder_; }
  const BurnMap& membrane_burn() const { return membrane_burn_; }
  const MembraneRemoval& membrane() const { return membrane_; }
  const SmokeEmitter& smoke() const { return smoke_; }
  /// Liver plus gallbladder area burnt past their damage thresholds, m^2.
  double damaged_area_m2() const;

  /// Deformed surfaces move the burn spread's centroids (topology unchanged).
  BurnMap& mutable_liver_burn() { return liver_; }
  BurnMap& mutable_gallbladder_burn() { return gallbladder_; }

 private:
  BurnMap& MapOf(CauterySurface surface);

  BurnMap liver_;
  BurnMap gallbladder_;
  BurnMap membrane_burn_;
  MembraneRemoval membrane_;
  SmokeEmitter smoke_;
  double time_s_ = 0;
};

}  // namespace vesica::fx
