#include "physics/calot/triangle_structures.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace vesica::physics::calot {
namespace {

/// Closest points of segments [p0, p1] and [q0, q1] (Ericson, Real-Time Collision Detection
/// 5.1.9): parameters along each, both in [0, 1].
std::pair<double, double> ClosestSegmentParameters(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1,
                                                   const Eigen::Vector3d& q0, const Eigen::Vector3d& q1) {
  const Eigen::Vector3d d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
  const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
  constexpr double kTiny = 1e-18;
  if (a <= kTiny && e <= kTiny) return {0.0, 0.0};
  if (a <= kTiny) return {0.0, std::clamp(f / e, 0.0, 1.0)};
  const double c = d1.dot(r);
  if (e <= kTiny) return {std::clamp(-c / a, 0.0, 1.0), 0.0};
  const double b = d1.dot(d2), denominator = a * e - b * b;
  double s = denominator > kTiny ? std::clamp((b * f - c * e) / denominator, 0.0, 1.0) : 0.0;
  double t = (b * s + f) / e;
  if (t < 0.0) {
    t = 0.0;
    s = std::clamp(-c / a, 0.0, 1.0);
  } else if (t > 1.0) {
    t = 1.0;
    s = std::clamp((b - c) / a, 0.0, 1.0);
  }
  return {s, t};
}

struct RodNodes {
  std::vector<Eigen::Vector3d> rest, position, velocity;
  std::vector<double> coordinate;
  std::vector<NodeHold> hold;
  std::vector<Eigen::Vector3d> target;
  void Add(const TubeRod& rod, int i) {
    rest.push_back(rod.rest_points_m().row(i).transpose());
    position.push_back(rod.positions_m().row(i).transpose());
    velocity.push_back(rod.velocities_m_per_s().row(i).transpose());
    coordinate.push_back(rod.material_coordinates_m()[static_cast<std::size_t>(i)]);
    hold.push_back(rod.hold(i));
    target.push_back(rod.hold(i) == NodeHold::kCoupled ? rod.coupling_target_m(i) : Eigen::Vector3d::Zero());
  }
  TubeRod Build(const TubeRod& from) const {
    const auto n = static_cast<Eigen::Index>(rest.size());
    RodPoints r(n, 3), x(n, 3), v(n, 3);
    for (Eigen::Index i = 0; i < n; ++i) {
      r.row(i) = rest[static_cast<std::size_t>(i)].transpose();
      x.row(i) = position[static_cast<std::size_t>(i)].transpose();
      v.row(i) = velocity[static_cast<std::size_t>(i)].transpose();
    }
    TubeRod rod(r, x, v, coordinate, from.material(), from.settings());
    for (int i = 0; i < static_cast<int>(n); ++i) {
      if (hold[static_cast<std::size_t>(i)] == NodeHold::kFixed) rod.HoldFixed(i);
      if (hold[static_cast<std::size_t>(i)] == NodeHold::kCoupled)
        rod.CoupleToTarget(i, target[static_cast<std::size_t>(i)]);
    }
    return rod;
  }
};

}  // namespace

TriangleStructures::TriangleStructures(const TriangleDescription& description) : description_(description) {
  ValidateTriangleDescription(description_);
  for (int t = 0; t < num_tubes(); ++t) {
    const TubeDescription& d = description_.tubes[static_cast<std::size_t>(t)];
    const RodPoints points = ResampleCentreline(d.centreline_m, d.node_spacing_m);
    TubeRod rod(points, {}, d.material, description_.rod_settings);
    const int n = rod.num_nodes();
    rod.HoldFixed(0);
    rod.HoldFixed(1);
    if (d.end_hold == TubeEndHold::kClamped) {
      rod.HoldFixed(n - 1);
      if (n > 3) rod.HoldFixed(n - 2);
    } else if (d.end_hold == TubeEndHold::kNeck) {
      rod.CoupleToTarget(n - 1, points.row(n - 1).transpose());
    }
    lengths_m_.push_back(rod.end_coordinate_m());
    rest_points_.push_back(points);
    rest_coordinates_.push_back(rod.material_coordinates_m());
    pieces_.push_back(TubePiece{t, std::move(rod), false, false});
  }
}

void TriangleStructures::CheckTube(int tube, const char* what) const {
  if (tube < 0 || tube >= num_tubes())
    throw std::out_of_range(std::string("TriangleStructures::") + what + ": no tube " + std::to_string(tube) +
                            " (have " + std::to_string(num_tubes()) + ")");
}

double TriangleStructures::TubeLength_m(int tube) const {
  CheckTube(tube, "TubeLength_m");
  return lengths_m_[static_cast<std::size_t>(tube)];
}

void TriangleStructures::Step(const Eigen::Vector3d& p_Neck_W_m) {
  const Eigen::Vector3d neck_shift = p_Neck_W_m - description_.p_Neck_W_m;
  for (TubePiece& piece : pieces_) {
    const RodPoints& rest = rest_points_[static_cast<std::size_t>(piece.tube)];
    for (int i = 0; i < piece.rod.num_nodes(); ++i)
      if (piece.rod.hold(i) == NodeHold::kCoupled)
        piece.rod.SetCouplingTarget(i, rest.row(rest.rows() - 1).transpose() + neck_shift);
    piece.rod.Step();
  }
}

Eigen::Vector3d TriangleStructures::NeckForce_N() const {
  Eigen::Vector3d force = Eigen::Vector3d::Zero();
  for (const TubePiece& piece : pieces_)
    for (int i = 0; i < piece.rod.num_nodes(); ++i)
      if (piece.rod.hold(i) == NodeHold::kCoupled) force += piece.rod.CouplingForceOnTarget_N(i);
  return force;
}

double TriangleStructures::NeckStiffness_N_per_m() const {
  double stiffness = 0;
  for (const TubePiece& piece : pieces_) {
    const TubeRod& rod = piece.rod;
    const int last = rod.num_nodes() - 1;
    const bool to_neck = rod.hold(last) == NodeHold::kCoupled || rod.hold(0) == NodeHold::kCoupled;
    if (!to_neck || piece.starts_at_cut || piece.ends_at_cut) continue;  // a stump pulls only by its weight
    double length_m = 0;
    for (const double l : rod.rest_lengths_m()) length_m += l;
    const double axial = rod.material().youngs_modulus_Pa * WallArea_m2(rod.material()) / length_m;
    const double coupling = rod.settings().coupling_stiffness_N_per_m;
    stiffness += 1.0 / (1.0 / axial + 1.0 / coupling);
  }
  return stiffness;
}

const TubePiece& TriangleStructures::PieceAt(int tube, double s_m) const {
  const TubePiece* nearest = nullptr;
  double nearest_gap = std::numeric_limits<double>::infinity();
  for (const TubePiece& piece : pieces_) {
    if (piece.tube != tube) continue;
    const double gap = std::max({0.0, piece.rod.start_coordinate_m() - s_m, s_m - piece.rod.end_coordinate_m()});
    if (gap < nearest_gap) {
      nearest_gap = gap;
      nearest = &piece;
    }
  }
  return *nearest;  // every tube has at least one piece
}

Eigen::Vector3d TriangleStructures::PositionAt(int tube, double s_m) const {
  CheckTube(tube, "PositionAt");
  return PieceAt(tube, s_m).rod.PositionAt(s_m);
}

Eigen::Vector3d TriangleStructures::RestPositionAt(int tube, double s_m) const {
  CheckTube(tube, "RestPositionAt");
  const std::vector<double>& sc = rest_coordinates_[static_cast<std::size_t>(tube)];
  const RodPoints& rest = rest_points_[static_cast<std::size_t>(tube)];
  const double s = std::clamp(s_m, sc.front(), sc.back());
  const auto upper = std::upper_bound(sc.begin(), sc.end(), s);
  const int i = std::clamp(static_cast<int>(upper - sc.begin()) - 1, 0, static_cast<int>(sc.size()) - 2);
  const double f =
      (s - sc[static_cast<std::size_t>(i)]) / (sc[static_cast<std::size_t>(i) + 1] - sc[static_cast<std::size_t>(i)]);
  return ((1.0 - f) * rest.row(i) + f * rest.row(i + 1)).transpose();
}

std::optional<TubeHit> TriangleStructures::NearestToSegment(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                                            double max_gap_m) const {
  std::optional<TubeHit> best;
  for (const TubePiece& piece : pieces_) {
    const TubeRod& rod = piece.rod;
    const double radius = rod.material().outer_radius_m;
    for (int i = 0; i + 1 < rod.num_nodes(); ++i) {
      const Eigen::Vector3d p0 = rod.positions_m().row(i).transpose(), p1 = rod.positions_m().row(i + 1).transpose();
      const auto [u, v] = ClosestSegmentParameters(p0, p1, a, b);
      const Eigen::Vector3d on_tube = p0 + u * (p1 - p0), on_tool = a + v * (b - a);
      const double distance = (on_tube - on_tool).norm();
      if (distance - radius > max_gap_m) continue;
      if (best && distance - radius >= best->surface_gap_m) continue;
      const double s0 = rod.material_coordinates_m()[static_cast<std::size_t>(i)];
      const double s1 = rod.material_coordinates_m()[static_cast<std::size_t>(i) + 1];
      best = TubeHit{piece.tube, s0 + u * (s1 - s0), on_tube, on_tool, distance, distance - radius};
    }
  }
  return best;
}

double TriangleStructures::PushByTip(const Eigen::Vector3d& p_Tip_W_m, double tip_radius_m) {
  double deepest = 0.0;
  for (TubePiece& piece : pieces_) deepest = std::max(deepest, piece.rod.PushOutOfSphere(p_Tip_W_m, tip_radius_m));
  return deepest;
}

ToolActionResult TriangleStructures::PlaceClip(int tube, double s_m) {
  CheckTube(tube, "PlaceClip");
  if (!(s_m > 0.0 && s_m < TubeLength_m(tube))) return ToolActionResult::kOutsideTube;
  for (const CutTube& cut : cuts_)
    if (cut.tube == tube && std::abs(cut.s_m - s_m) < kClipHalfWidth_m) return ToolActionResult::kAlreadyCut;
  for (const ClipOnTube& clip : clips_)
    if (clip.tube == tube && std::abs(clip.s_m - s_m) < 2.0 * kClipHalfWidth_m) return ToolActionResult::kOnClip;
  clips_.push_back({tube, s_m});
  return ToolActionResult::kDone;
}

Eigen::Vector3d TriangleStructures::ClipPosition(int clip) const {
  if (clip < 0 || clip >= static_cast<int>(clips_.size()))
    throw std::out_of_range("TriangleStructures::ClipPosition: no clip " + std::to_string(clip) + " (have " +
                            std::to_string(clips_.size()) + ")");
  const ClipOnTube& c = clips_[static_cast<std::size_t>(clip)];
  return PositionAt(c.tube, c.s_m);
}

ToolActionResult TriangleStructures::Cut(int tube, double s_m) {
  CheckTube(tube, "Cut");
  if (!(s_m > 0.0 && s_m < TubeLength_m(tube))) return ToolActionResult::kOutsideTube;
  for (const ClipOnTube& clip : clips_)
    if (clip.tube == tube && std::abs(clip.s_m - s_m) < kClipHalfWidth_m) return ToolActionResult::kOnClip;
  auto it = std::find_if(pieces_.begin(), pieces_.end(), [&](const TubePiece& p) {
    return p.tube == tube && s_m > p.rod.start_coordinate_m() + 1e-4 && s_m < p.rod.end_coordinate_m() - 1e-4;
  });
  if (it == pieces_.end()) return ToolActionResult::kAlreadyCut;  // within 0.1 mm of an open end
  const TubeRod& rod = it->rod;
  const int n = rod.num_nodes();
  const auto [i, f] = rod.SegmentAt(s_m);
  auto lerp = [f = f](const RodPoints& m, int k) -> Eigen::Vector3d {
    return ((1.0 - f) * m.row(k) + f * m.row(k + 1)).transpose();
  };
  // Two nodes at the cut, one on each piece. A node that would sit under a quarter segment from
  // the cut is dropped (unless the rod holds it) so no piece gets a sliver of a segment; a held
  // node that has to go passes its hold to the cut node.
  RodNodes left, right;
  const bool drop_left = (f < 0.25 && i >= 1 && rod.hold(i) == NodeHold::kFree) || f < 1e-6;
  const bool drop_right = (f > 0.75 && i + 1 <= n - 2 && rod.hold(i + 1) == NodeHold::kFree) || f > 1.0 - 1e-6;
  for (int k = 0; k <= (drop_left ? i - 1 : i); ++k) left.Add(rod, k);
  left.rest.push_back(lerp(rod.rest_points_m(), i));
  left.position.push_back(lerp(rod.positions_m(), i));
  left.velocity.push_back(lerp(rod.velocities_m_per_s(), i));
  left.coordinate.push_back(s_m);
  left.hold.push_back(drop_left && rod.hold(i) == NodeHold::kFixed ? NodeHold::kFixed : NodeHold::kFree);
  left.target.push_back(Eigen::Vector3d::Zero());
  right.rest.push_back(lerp(rod.rest_points_m(), i));
  right.position.push_back(lerp(rod.positions_m(), i));
  right.velocity.push_back(lerp(rod.velocities_m_per_s(), i));
  right.coordinate.push_back(s_m);
  right.hold.push_back(drop_right && rod.hold(i + 1) == NodeHold::kFixed ? NodeHold::kFixed : NodeHold::kFree);
  right.target.push_back(Eigen::Vector3d::Zero());
  for (int k = drop_right ? i + 2 : i + 1; k < n; ++k) right.Add(rod, k);
  if (left.rest.size() < 2 || right.rest.size() < 2) return ToolActionResult::kOutsideTube;
  TubePiece before{tube, left.Build(rod), it->starts_at_cut, true};
  TubePiece after{tube, right.Build(rod), true, it->ends_at_cut};
  *it = std::move(before);
  pieces_.insert(it + 1, std::move(after));
  cuts_.push_back({tube, s_m});
  return ToolActionResult::kDone;
}

TubeFlowState TriangleStructures::FlowState(int tube) const {
  CheckTube(tube, "FlowState");
  const TubeDescription& d = description_.tubes[static_cast<std::size_t>(tube)];
  TubeFlowState state;
  state.length_m = TubeLength_m(tube);
  state.start_pressurised = d.start_pressurised;
  state.end_pressurised = d.end_pressurised;
  for (const ClipOnTube& clip : clips_)
    if (clip.tube == tube) state.clips_s_m.push_back(clip.s_m);
  for (const CutTube& cut : cuts_)
    if (cut.tube == tube) state.cuts_s_m.push_back(cut.s_m);
  return state;
}

bool TriangleStructures::FluidAt(int tube, double s_m) const { return calot::FluidAt(FlowState(tube), s_m); }

bool TriangleStructures::FlowPasses(int tube, double s_m) const { return calot::FlowPasses(FlowState(tube), s_m); }

std::vector<TubeLeak> TriangleStructures::Leaks() const {
  std::vector<TubeLeak> leaks;
  for (int t = 0; t < num_tubes(); ++t)
    for (const OpenEndLeak& end : LeakingEnds(FlowState(t))) {
      // The stump's own rod: the piece that ends (patient's side) or starts at the cut.
      Eigen::Vector3d p = PositionAt(t, end.s_m);
      for (const TubePiece& piece : pieces_)
        if (piece.tube == t &&
            ((end.patient_side && piece.ends_at_cut && piece.rod.end_coordinate_m() == end.s_m) ||
             (!end.patient_side && piece.starts_at_cut && piece.rod.start_coordinate_m() == end.s_m)))
          p = piece.rod.PositionAt(end.s_m);
      leaks.push_back({t, FluidOf(description_.tubes[static_cast<std::size_t>(t)].kind), end.s_m, end.patient_side, p});
    }
  return leaks;
}

bool TriangleStructures::Bleeding() const {
  const std::vector<TubeLeak> leaks = Leaks();
  return std::any_of(leaks.begin(), leaks.end(), [](const TubeLeak& l) { return l.fluid == Fluid::kBlood; });
}

bool TriangleStructures::BileLeaking() const {
  const std::vector<TubeLeak> leaks = Leaks();
  return std::any_of(leaks.begin(), leaks.end(), [](const TubeLeak& l) { return l.fluid == Fluid::kBile; });
}

}  // namespace vesica::physics::calot
