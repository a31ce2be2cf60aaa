#pragma once
// What the triangle's tubes are, as data: centrelines, radii, walls, how their ends are held and
// which ends are under pressure, so anatomical variants come from the scenario, not from code.
// Material coordinates run from a tube's first centreline point (the patient's side, where it is
// held: hilum, junction or right hepatic artery) to its last (for the cystic duct and artery,
// the gallbladder's neck).

#include <Eigen/Core>
#include <string>
#include <vector>

#include "physics/calot/tube_kind.h"
#include "physics/calot/tube_material.h"
#include "physics/calot/tube_rod.h"

namespace vesica::physics::calot {

enum class TubeEndHold {
  kClamped,  ///< held in place and direction (the first two nodes, or the last two, fixed)
  kNeck,     ///< tied to the gallbladder's neck, which the scene moves (end only)
  kFree,
};

struct TubeDescription {
  std::string name;  ///< as the scenario names it, for messages
  TubeKind kind = TubeKind::kCysticDuct;
  std::vector<Eigen::Vector3d> centreline_m;  ///< >= 2 points, patient's side first, m
  TubeMaterial material;                      ///< radius, wall, E, densities (DefaultTubeMaterial)
  double node_spacing_m = 0.0025;             ///< the rod's rest segment length (about), > 0
  TubeEndHold end_hold = TubeEndHold::kNeck;  ///< the start is always clamped
  bool start_pressurised = true;              ///< fluid under pressure behind the start (bile, arterial blood)
  bool end_pressurised = true;                ///< behind the end (the gallbladder's bile; false for the artery)
  std::string source = "";                    ///< where it was read ("file.toml:42"), for errors
};

struct TriangleDescription {
  std::vector<TubeDescription> tubes;
  TubeRodSettings rod_settings;
  /// Where the gallbladder's neck is when the tubes are at rest; Step's neck position moves
  /// each neck-held end by the neck's displacement from here.
  Eigen::Vector3d p_Neck_W_m = Eigen::Vector3d::Zero();
};

/// Literature values for a kind (docs/calot.md): cystic duct 3 mm, artery 2 mm, common hepatic
/// duct 5 mm, common bile duct 6.5 mm outer diameter; walls and Young's moduli.
TubeMaterial DefaultTubeMaterial(TubeKind kind);

/// The default scenario's triangle (data/scenarios/cholecystectomy.toml's context tubes): cystic
/// duct and artery to the neck, common hepatic and common bile duct clamped at both ends.
TriangleDescription DefaultTriangleDescription();

/// Throws std::invalid_argument naming the tube (and its source) and the field.
void ValidateTriangleDescription(const TriangleDescription& description);

/// The polyline resampled at equal arc-length steps of about spacing_m (at least 2 segments):
/// #points by 3.
RodPoints ResampleCentreline(const std::vector<Eigen::Vector3d>& centreline_m, double spacing_m);

}  // namespace vesica::physics::calot
