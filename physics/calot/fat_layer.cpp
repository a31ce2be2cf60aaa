#include "physics/calot/fat_layer.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace vesica::physics::calot {
namespace {

void Require(bool ok, const char* field, const char* range, double value) {
  if (!ok)
    throw std::invalid_argument(std::string("FatLayerDescription: ") + field + " must be " + range + ", got " +
                                std::to_string(value));
}

struct NearestOnTube {
  int tube = -1;
  double s_m = 0.0;
  double distance_m = std::numeric_limits<double>::infinity();
};

// A tube's rest centreline as a polyline with its material coordinates.
struct RestPolyline {
  std::vector<Eigen::Vector3d> points;
  std::vector<double> s;
};

}  // namespace

FatLayerDescription DefaultFatLayerDescription(const TriangleDescription& triangle) {
  const TubeDescription* duct = nullptr;
  const TubeDescription* hepatic = nullptr;
  for (const TubeDescription& tube : triangle.tubes) {
    if (tube.kind == TubeKind::kCysticDuct && !duct) duct = &tube;
    if (tube.kind == TubeKind::kCommonHepaticDuct && !hepatic) hepatic = &tube;
  }
  if (!duct || !hepatic || duct->centreline_m.empty() || hepatic->centreline_m.empty())
    throw std::invalid_argument(
        "DefaultFatLayerDescription: the triangle needs a cystic duct and a common hepatic duct for its corners");
  FatLayerDescription d;
  d.corners_m = {duct->centreline_m.front(), triangle.p_Neck_W_m, hepatic->centreline_m.front()};
  return d;
}

FatLayer::FatLayer(const FatLayerDescription& description, const TriangleStructures& structures)
    : description_(description) {
  const FatLayerDescription& d = description_;
  Require(d.cell_spacing_m > 0, "cell_spacing_m", "> 0", d.cell_spacing_m);
  Require(d.slab_thickness_m > 0, "slab_thickness_m", "> 0", d.slab_thickness_m);
  Require(d.sleeve_thickness_m >= 0, "sleeve_thickness_m", ">= 0", d.sleeve_thickness_m);
  Require(d.density_kg_per_m3 > 0, "density_kg_per_m3", "> 0", d.density_kg_per_m3);
  Require(d.ablation_energy_J_per_kg > 0, "ablation_energy_J_per_kg", "> 0", d.ablation_energy_J_per_kg);
  Require(d.tear_strain > 0, "tear_strain", "> 0", d.tear_strain);
  Require(d.anchor_reach_m >= 0, "anchor_reach_m", ">= 0", d.anchor_reach_m);
  Require(d.cover_margin_m > 0, "cover_margin_m", "> 0", d.cover_margin_m);
  Require(d.tube_sample_spacing_m > 0, "tube_sample_spacing_m", "> 0", d.tube_sample_spacing_m);
  const Eigen::Vector3d a = d.corners_m[0], b = d.corners_m[1], c = d.corners_m[2];
  const Eigen::Vector3d normal_raw = (b - a).cross(c - a);
  if (!(normal_raw.norm() > 1e-8)) throw std::invalid_argument("FatLayerDescription: corners_m are collinear");
  const Eigen::Vector3d normal = normal_raw.normalized();

  // The tubes' rest centrelines, sampled at a millimetre.
  std::vector<RestPolyline> tubes(static_cast<std::size_t>(structures.num_tubes()));
  std::vector<double> radii;
  Eigen::Vector3d lo = a.cwiseMin(b).cwiseMin(c), hi = a.cwiseMax(b).cwiseMax(c);
  double reach = d.slab_thickness_m;
  for (int t = 0; t < structures.num_tubes(); ++t) {
    const double length = structures.TubeLength_m(t);
    const int count = std::max(2, static_cast<int>(std::ceil(length / 0.001)) + 1);
    for (int k = 0; k < count; ++k) {
      const double s = length * k / (count - 1);
      tubes[static_cast<std::size_t>(t)].points.push_back(structures.RestPositionAt(t, s));
      tubes[static_cast<std::size_t>(t)].s.push_back(s);
      lo = lo.cwiseMin(tubes[static_cast<std::size_t>(t)].points.back());
      hi = hi.cwiseMax(tubes[static_cast<std::size_t>(t)].points.back());
    }
    radii.push_back(structures.description().tubes[static_cast<std::size_t>(t)].material.outer_radius_m);
    reach = std::max(reach, radii.back() + d.sleeve_thickness_m);
  }
  auto nearest_on_tubes = [&](const Eigen::Vector3d& p) {
    NearestOnTube best;
    for (std::size_t t = 0; t < tubes.size(); ++t) {
      const RestPolyline& line = tubes[t];
      for (std::size_t k = 0; k + 1 < line.points.size(); ++k) {
        const Eigen::Vector3d e = line.points[k + 1] - line.points[k];
        const double f = std::clamp((p - line.points[k]).dot(e) / e.squaredNorm(), 0.0, 1.0);
        const double distance = (line.points[k] + f * e - p).norm();
        if (distance < best.distance_m)
          best = {static_cast<int>(t), line.s[k] + f * (line.s[k + 1] - line.s[k]), distance};
      }
    }
    return best;
  };
  auto inside_triangle_prism = [&](const Eigen::Vector3d& p) {
    if (std::abs((p - a).dot(normal)) > 0.5 * d.slab_thickness_m) return false;
    // Barycentric coordinates of p's projection.
    const Eigen::Vector3d q = p - (p - a).dot(normal) * normal;
    const double area = normal_raw.norm();
    const double wa = (c - b).cross(q - b).dot(normal) / area, wb = (a - c).cross(q - c).dot(normal) / area;
    return wa >= 0 && wb >= 0 && 1.0 - wa - wb >= 0;
  };

  lo.array() -= reach;
  hi.array() += reach;
  const double h = d.cell_spacing_m;
  const Eigen::Vector3i counts = ((hi - lo) / h).array().ceil().cast<int>();
  for (int i = 0; i <= counts.x(); ++i)
    for (int j = 0; j <= counts.y(); ++j)
      for (int k = 0; k <= counts.z(); ++k) {
        const Eigen::Vector3d p = lo + h * Eigen::Vector3d(i, j, k);
        const NearestOnTube near = nearest_on_tubes(p);
        const double radius = near.tube >= 0 ? radii[static_cast<std::size_t>(near.tube)] : 0.0;
        if (near.tube >= 0 && near.distance_m < radius) continue;  // inside a tube
        const bool in_triangle = inside_triangle_prism(p);
        const bool in_sleeve = near.tube >= 0 && near.distance_m <= radius + d.sleeve_thickness_m;
        if (!in_triangle && !in_sleeve) continue;
        FatCell cell;
        cell.p_Rest_W_m = p;
        cell.in_triangle = in_triangle;
        if (near.tube >= 0 && near.distance_m <= radius + d.anchor_reach_m) {
          cell.anchor_tube = near.tube;
          cell.anchor_s_m = near.s_m;
          cell.p_AnchorRest_W_m = structures.RestPositionAt(near.tube, near.s_m);
        }
        cells_.push_back(cell);
      }
  positions_.resize(cells_.size());

  // Tube samples and the cells near enough to hide each (candidates, tested at current positions).
  samples_per_tube_.assign(static_cast<std::size_t>(structures.num_tubes()), 0);
  for (int t = 0; t < structures.num_tubes(); ++t) {
    const double length = structures.TubeLength_m(t);
    const int count = std::max(2, static_cast<int>(std::ceil(length / d.tube_sample_spacing_m)));
    for (int k = 0; k < count; ++k) {
      TubeSample sample;
      sample.tube = t;
      sample.s_m = length * (k + 0.5) / count;  // each sample stands for an equal share of the length
      sample.radius_m = radii[static_cast<std::size_t>(t)];
      const Eigen::Vector3d p = structures.RestPositionAt(t, sample.s_m);
      const double candidate_reach = 2.0 * (sample.radius_m + d.cover_margin_m) + d.tear_strain * d.cell_spacing_m;
      for (std::size_t i = 0; i < cells_.size(); ++i)
        if ((cells_[i].p_Rest_W_m - p).norm() <= candidate_reach) sample.nearby_cells.push_back(static_cast<int>(i));
      samples_.push_back(std::move(sample));
    }
    samples_per_tube_[static_cast<std::size_t>(t)] = count;
  }
  Update(structures);
}

double FatLayer::CellRemovalEnergy_J() const {
  const double h = description_.cell_spacing_m;
  return description_.ablation_energy_J_per_kg * description_.density_kg_per_m3 * h * h * h;
}

double FatLayer::Integrity(int index) const {
  const FatCell& cell = cells_.at(static_cast<std::size_t>(index));
  if (cell.state != FatCellState::kIntact) return 0.0;
  return std::clamp(1.0 - cell.dose_J / CellRemovalEnergy_J() -
                        cell.max_displacement_m / (description_.tear_strain * description_.cell_spacing_m),
                    0.0, 1.0);
}

void FatLayer::Remove(FatCell& cell, FatCellState why) { cell.state = why; }

void FatLayer::Update(const TriangleStructures& structures) {
  for (std::size_t i = 0; i < cells_.size(); ++i) {
    const FatCell& cell = cells_[i];
    Eigen::Vector3d p = cell.p_Rest_W_m + cell.displacement_m;
    if (cell.anchor_tube >= 0) p += structures.PositionAt(cell.anchor_tube, cell.anchor_s_m) - cell.p_AnchorRest_W_m;
    positions_[i] = p;
  }
  for (TubeSample& sample : samples_) {
    sample.p_W_m = structures.PositionAt(sample.tube, sample.s_m);
    const double cover = sample.radius_m + description_.cover_margin_m;
    sample.hidden = std::any_of(sample.nearby_cells.begin(), sample.nearby_cells.end(), [&](int i) {
      return cells_[static_cast<std::size_t>(i)].state == FatCellState::kIntact &&
             (positions_[static_cast<std::size_t>(i)] - sample.p_W_m).squaredNorm() <= cover * cover;
    });
  }
}

int FatLayer::Burn(const Eigen::Vector3d& p, double radius_m, double power_W, double dt_s) {
  if (!p.allFinite() || !(radius_m >= 0) || !(power_W >= 0) || !(dt_s >= 0))
    throw std::invalid_argument("FatLayer::Burn: the hook's position must be finite, radius, power and dt >= 0");
  std::vector<int> touched;
  for (std::size_t i = 0; i < cells_.size(); ++i)
    if (cells_[i].state == FatCellState::kIntact && (positions_[i] - p).squaredNorm() <= radius_m * radius_m)
      touched.push_back(static_cast<int>(i));
  if (touched.empty()) return 0;
  const double share_J = power_W * dt_s / static_cast<double>(touched.size());
  int removed = 0;
  for (int i : touched) {
    FatCell& cell = cells_[static_cast<std::size_t>(i)];
    cell.dose_J += share_J;
    if (Integrity(i) <= 0.0) {
      Remove(cell, FatCellState::kBurnt);
      ++removed;
    }
  }
  return removed;
}

int FatLayer::Push(const Eigen::Vector3d& p, double radius_m) {
  if (!p.allFinite() || !(radius_m >= 0))
    throw std::invalid_argument("FatLayer::Push: the tip's position must be finite and radius >= 0");
  int torn = 0;
  for (std::size_t i = 0; i < cells_.size(); ++i) {
    FatCell& cell = cells_[i];
    if (cell.state != FatCellState::kIntact) continue;
    const Eigen::Vector3d offset = positions_[i] - p;
    const double distance = offset.norm();
    if (distance >= radius_m) continue;
    // Out to the tip's surface, along the line from its centre (any direction when on it).
    const Eigen::Vector3d direction = distance > 1e-12 ? (offset / distance).eval() : Eigen::Vector3d::UnitX();
    const Eigen::Vector3d shift = (radius_m - distance) * direction;
    cell.displacement_m += shift;
    positions_[i] += shift;
    cell.max_displacement_m = std::max(cell.max_displacement_m, cell.displacement_m.norm());
    if (Integrity(static_cast<int>(i)) <= 0.0) {
      Remove(cell, FatCellState::kTorn);
      ++torn;
    }
  }
  return torn;
}

double FatLayer::RemovedFraction() const { return BurntFraction() + TornFraction(); }

double FatLayer::BurntFraction() const {
  const auto n =
      std::count_if(cells_.begin(), cells_.end(), [](const FatCell& c) { return c.state == FatCellState::kBurnt; });
  return cells_.empty() ? 0.0 : static_cast<double>(n) / static_cast<double>(cells_.size());
}

double FatLayer::TornFraction() const {
  const auto n =
      std::count_if(cells_.begin(), cells_.end(), [](const FatCell& c) { return c.state == FatCellState::kTorn; });
  return cells_.empty() ? 0.0 : static_cast<double>(n) / static_cast<double>(cells_.size());
}

double FatLayer::TriangleClearedFraction() const {
  std::size_t in = 0, cleared = 0;
  for (const FatCell& c : cells_)
    if (c.in_triangle) {
      ++in;
      if (c.state != FatCellState::kIntact) ++cleared;
    }
  return in == 0 ? 0.0 : static_cast<double>(cleared) / static_cast<double>(in);
}

double FatLayer::UncoveredFraction(int tube) const {
  if (tube < 0 || tube >= static_cast<int>(samples_per_tube_.size()))
    throw std::out_of_range("FatLayer::UncoveredFraction: no tube " + std::to_string(tube));
  std::size_t uncovered = 0;
  for (const TubeSample& sample : samples_)
    if (sample.tube == tube && !sample.hidden) ++uncovered;
  return static_cast<double>(uncovered) / static_cast<double>(samples_per_tube_[static_cast<std::size_t>(tube)]);
}

}  // namespace vesica::physics::calot
