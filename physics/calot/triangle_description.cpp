#include "physics/calot/triangle_description.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace vesica::physics::calot {
namespace {

std::string Where(const TubeDescription& tube, std::size_t index) {
  std::string where =
      "tube " + std::to_string(index) + " (" + (tube.name.empty() ? TubeKindName(tube.kind) : tube.name);
  if (!tube.source.empty()) where += ", " + tube.source;
  return where + ")";
}

TubeDescription Tube(const char* name, TubeKind kind, std::vector<Eigen::Vector3d> centreline, TubeEndHold end_hold) {
  TubeDescription tube;
  tube.name = name;
  tube.kind = kind;
  tube.centreline_m = std::move(centreline);
  tube.material = DefaultTubeMaterial(kind);
  tube.end_hold = end_hold;
  // The artery's gallbladder side bleeds back only a little (collaterals): not a leak here.
  tube.end_pressurised = kind != TubeKind::kCysticArtery;
  return tube;
}

}  // namespace

TubeMaterial DefaultTubeMaterial(TubeKind kind) {
  TubeMaterial m;
  switch (kind) {
    case TubeKind::kCysticDuct:  // ~3 mm across, thin wall
      m.outer_radius_m = 0.0015;
      m.wall_thickness_m = 0.0005;
      m.youngs_modulus_Pa = 1.0e6;
      break;
    case TubeKind::kCysticArtery:  // ~2 mm across, a small muscular artery
      m.outer_radius_m = 0.0010;
      m.wall_thickness_m = 0.0003;
      m.youngs_modulus_Pa = 1.5e6;
      m.content_density_kg_per_m3 = 1060.0;
      break;
    case TubeKind::kCommonHepaticDuct:  // ~5 mm
      m.outer_radius_m = 0.0025;
      m.wall_thickness_m = 0.0008;
      m.youngs_modulus_Pa = 1.0e6;
      break;
    case TubeKind::kCommonBileDuct:  // ~6.5 mm
      m.outer_radius_m = 0.00325;
      m.wall_thickness_m = 0.0008;
      m.youngs_modulus_Pa = 1.0e6;
      break;
  }
  return m;
}

TriangleDescription DefaultTriangleDescription() {
  // data/scenarios/cholecystectomy.toml's [[context_organs]] tubes, each from the patient's side
  // (the scenario lists the cystic duct from the gallbladder down: reversed here).
  const Eigen::Vector3d junction(-0.0034, -0.0635, 0.0273), neck(-0.0173, -0.0170, 0.0477);
  TriangleDescription d;
  d.p_Neck_W_m = neck;
  d.tubes.push_back(
      Tube("cystic duct", TubeKind::kCysticDuct, {junction, {-0.0134, -0.0412, 0.0372}, neck}, TubeEndHold::kNeck));
  d.tubes.push_back(Tube("cystic artery", TubeKind::kCysticArtery,
                         {{0.0174, -0.0369, 0.0529}, {0.0009, -0.0307, 0.0448}, {-0.0207, -0.0142, 0.0446}},
                         TubeEndHold::kNeck));
  d.tubes.push_back(Tube("common hepatic duct", TubeKind::kCommonHepaticDuct,
                         {{0.0210, -0.0375, 0.0555}, {0.0149, -0.0525, 0.0411}, junction}, TubeEndHold::kClamped));
  d.tubes.push_back(Tube("common bile duct", TubeKind::kCommonBileDuct,
                         {junction, {-0.0078, -0.0778, 0.0145}, {-0.0089, -0.0983, -0.0066}}, TubeEndHold::kClamped));
  return d;
}

void ValidateTriangleDescription(const TriangleDescription& description) {
  if (description.tubes.empty()) throw std::invalid_argument("TriangleDescription: no tubes");
  if (!description.p_Neck_W_m.allFinite()) throw std::invalid_argument("TriangleDescription: p_Neck_W_m is not finite");
  for (std::size_t i = 0; i < description.tubes.size(); ++i) {
    const TubeDescription& tube = description.tubes[i];
    const std::string where = Where(tube, i);
    if (tube.centreline_m.size() < 2)
      throw std::invalid_argument(where + ": centreline_m needs at least 2 points, got " +
                                  std::to_string(tube.centreline_m.size()));
    for (std::size_t k = 0; k < tube.centreline_m.size(); ++k) {
      if (!tube.centreline_m[k].allFinite())
        throw std::invalid_argument(where + ": centreline_m[" + std::to_string(k) + "] is not finite");
      if (k > 0 && (tube.centreline_m[k] - tube.centreline_m[k - 1]).norm() < 1e-6)
        throw std::invalid_argument(where + ": centreline_m[" + std::to_string(k) + "] repeats the point before it");
    }
    if (!(tube.node_spacing_m > 0))
      throw std::invalid_argument(where + ": node_spacing_m must be > 0, got " + std::to_string(tube.node_spacing_m));
    ValidateTubeMaterial(tube.material, where.c_str());
  }
}

RodPoints ResampleCentreline(const std::vector<Eigen::Vector3d>& centreline_m, double spacing_m) {
  std::vector<double> arc{0.0};
  for (std::size_t k = 1; k < centreline_m.size(); ++k)
    arc.push_back(arc.back() + (centreline_m[k] - centreline_m[k - 1]).norm());
  const int segments = std::max(2, static_cast<int>(std::lround(arc.back() / spacing_m)));
  RodPoints points(segments + 1, 3);
  std::size_t k = 1;
  for (int i = 0; i <= segments; ++i) {
    const double s = arc.back() * i / segments;
    while (k + 1 < arc.size() && arc[k] < s) ++k;
    const double f = std::clamp((s - arc[k - 1]) / (arc[k] - arc[k - 1]), 0.0, 1.0);
    points.row(i) = ((1.0 - f) * centreline_m[k - 1] + f * centreline_m[k]).transpose();
  }
  return points;
}

}  // namespace vesica::physics::calot
