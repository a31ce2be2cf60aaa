#include "app/session/calot_triangle_step.h"

#include <spdlog/spdlog.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "physics/instrument/instrument_pose.h"
#include "physics/tissue/connective_tissue.h"

namespace vesica::app {

namespace {

calot::StructureKind StructureKindOf(physics::calot::TubeKind kind) {
  switch (kind) {
    case physics::calot::TubeKind::kCysticDuct:
      return calot::StructureKind::kCysticDuct;
    case physics::calot::TubeKind::kCysticArtery:
      return calot::StructureKind::kCysticArtery;
    case physics::calot::TubeKind::kCommonHepaticDuct:
      return calot::StructureKind::kCommonHepaticDuct;
    case physics::calot::TubeKind::kCommonBileDuct:
      return calot::StructureKind::kCommonBileDuct;
  }
  return calot::StructureKind::kCommonBileDuct;
}

// Gallbladder FEM nodes within `radius_m` of the neck at rest; the 4 nearest when none is (a
// neck drawn a little off the mesh still follows it).
std::vector<int> NeckNodes(const physics::Vertices& rest, const Eigen::Vector3d& p_Neck_W_m, double radius_m) {
  std::vector<std::pair<double, int>> by_distance;
  std::vector<int> nodes;
  for (Eigen::Index v = 0; v < rest.rows(); ++v) {
    const double d = (rest.row(v).transpose() - p_Neck_W_m).norm();
    if (d <= radius_m) nodes.push_back(static_cast<int>(v));
    by_distance.emplace_back(d, static_cast<int>(v));
  }
  if (!nodes.empty()) return nodes;
  if (by_distance.empty()) throw std::invalid_argument("Calot's triangle: the gallbladder has no nodes for the neck");
  const auto n = std::min<std::size_t>(4, by_distance.size());
  std::partial_sort(by_distance.begin(), by_distance.begin() + static_cast<long>(n), by_distance.end());
  for (std::size_t i = 0; i < n; ++i) nodes.push_back(by_distance[i].second);
  return nodes;
}

// Springs whose gallbladder end lies, at rest, in the third of the gallbladder nearest the neck
// (along the line from the neck through the gallbladder's centroid).
std::vector<int> LowerThirdSprings(const physics::DissectionModel& model, const Eigen::Vector3d& p_Neck_W_m) {
  const physics::Vertices& rest = model.gallbladder->rest_mesh.vertices;
  const Eigen::Vector3d centroid = rest.colwise().mean().transpose();
  Eigen::Vector3d axis = centroid - p_Neck_W_m;
  if (axis.norm() < 1e-9) return {};
  axis.normalize();
  double t_min = std::numeric_limits<double>::infinity(), t_max = -t_min;
  for (Eigen::Index v = 0; v < rest.rows(); ++v) {
    const double t = (rest.row(v).transpose() - p_Neck_W_m).dot(axis);
    t_min = std::min(t_min, t);
    t_max = std::max(t_max, t);
  }
  const double t_third = t_min + (t_max - t_min) / 3.0;
  std::vector<int> springs;
  const auto& all = model.tissue.springs;
  for (std::size_t s = 0; s < all.size(); ++s) {
    const Eigen::Vector3d end = physics::GallbladderEnd(all[s], rest, model.gallbladder->rest_mesh.tets);
    if ((end - p_Neck_W_m).dot(axis) <= t_third) springs.push_back(static_cast<int>(s));
  }
  return springs;
}

}  // namespace

CalotTriangleStep::CalotTriangleStep(const CalotSessionSetup& setup, const physics::DissectionScene& scene,
                                     const CalotToolGeometry& geometry)
    : setup_(setup), geometry_(geometry), h_s_(scene.model().settings.time_step_s), tubes_(ToPhysics(setup.triangle)) {
  fat_ = std::make_unique<physics::calot::FatLayer>(physics::calot::DefaultFatLayerDescription(tubes_.description()),
                                                    tubes_);
  const Eigen::Vector3d& neck = tubes_.description().p_Neck_W_m;
  neck_nodes_ = NeckNodes(scene.model().gallbladder->rest_mesh.vertices, neck, geometry_.neck_radius_m);
  p_Neck_W_m_ = neck;
  lower_third_springs_ = LowerThirdSprings(scene.model(), neck);
  liver_surface_ = organs_.AddSurface(scene.model().liver->rest_surface);
  gallbladder_surface_ = organs_.AddSurface(scene.model().gallbladder_boundary.surface);
  seen_fraction_.assign(tubes_.description().tubes.size(), 0.0);
  if (geometry_.visibility_period_steps < 1)
    throw std::invalid_argument("Calot's triangle: visibility_period_steps must be >= 1");
  if (!(setup_.camera.vertical_view_angle_rad > 0 && setup_.camera.vertical_view_angle_rad < std::numbers::pi) ||
      !(setup_.camera.aspect > 0))
    throw std::invalid_argument("Calot's triangle: the camera's view angle must be in (0, pi) and its aspect > 0");
}

std::array<Eigen::Vector3d, 2> CalotTriangleStep::RightJawSegment(const physics::DissectionScene& scene,
                                                                  const physics::InstrumentPose& pose) const {
  const physics::InstrumentMount& mount = scene.model().instruments[1];
  const Eigen::Vector3d shaft = physics::ShaftDirection(mount.reference_direction_W, pose);
  const Eigen::Vector3d tip = scene.tool_tip(1);
  return {tip - geometry_.jaw_length_m * shaft, tip};
}

std::array<Eigen::Vector3d, 2> CalotTriangleStep::GrasperJawTips(const physics::DissectionScene& scene,
                                                                 const physics::InstrumentPose& pose) const {
  const physics::InstrumentMount& mount = scene.model().instruments[0];
  const Eigen::Vector3d shaft = physics::ShaftDirection(mount.reference_direction_W, pose);
  // The jaws open in the plane the roll turns about the shaft; the hinge sits jaw_length behind the tip.
  Eigen::Vector3d side = shaft.cross(Eigen::Vector3d::UnitZ());
  if (side.norm() < 1e-6) side = shaft.cross(Eigen::Vector3d::UnitY());
  side.normalize();
  const Eigen::Vector3d across = std::cos(pose.roll_rad) * side + std::sin(pose.roll_rad) * shaft.cross(side);
  const double half_spread_m = geometry_.jaw_length_m * std::sin(0.5 * std::max(0.0, pose.jaw_angle_rad));
  const Eigen::Vector3d tip = scene.tool_tip(0);
  return {tip + half_spread_m * across, tip - half_spread_m * across};
}

void CalotTriangleStep::Step(const physics::DissectionScene& scene, const device::InputFrame& input, bool pedal_burns) {
  // The neck moves with its gallbladder nodes' mean displacement; the session puts the tubes'
  // pull back on those nodes (DissectionScene::SetOutsideLoad).
  const Eigen::VectorXd& u = scene.gallbladder().state().displacement_m;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const int v : neck_nodes_) mean += u.segment<3>(3 * v);
  mean /= static_cast<double>(neck_nodes_.size());
  p_Neck_W_m_ = tubes_.description().p_Neck_W_m + mean;
  tubes_.Step(p_Neck_W_m_);

  // The right hand acts first: its closing jaws take the tube where it lay between them.
  ActWithRightTool(scene, input, pedal_burns);
  // A tip pushes the tubes aside, unless its jaws are open (they straddle a tube, not push it).
  for (int i = 0; i < 2; ++i) {
    const bool jaws = i == 0 || input.right_tool == physics::InstrumentTool::kClipApplier ||
                      input.right_tool == physics::InstrumentTool::kScissors;
    if (jaws && input.instruments[static_cast<std::size_t>(i)].pose.jaw_angle_rad > geometry_.jaw_open_rad) continue;
    const bool hook = i == 1 && input.right_tool == physics::InstrumentTool::kCauteryHook;
    tubes_.PushByTip(scene.tool_tip(i), hook ? geometry_.hook_wire_radius_m : geometry_.tip_radius_m);
  }
  // Blunt dissection: the grasper's jaw tips push the fat (open jaws spread it).
  for (const Eigen::Vector3d& jaw_tip : GrasperJawTips(scene, input.instruments[0].pose))
    fat_->Push(jaw_tip, geometry_.tip_radius_m);
  fat_->Update(tubes_);

  ++steps_;
  FillSnapshot(scene);
  if (!assessment_stopped_) {
    try {
      metrics_.Observe(snapshot_);
    } catch (const calot::CalotInputError& e) {
      // A bug upstream of the training logic: say so once and stop judging rather than crash.
      spdlog::error("Calot's triangle: assessment stopped: {}", e.what());
      assessment_stopped_ = true;
    }
  }
}

void CalotTriangleStep::ActWithRightTool(const physics::DissectionScene& scene, const device::InputFrame& input,
                                         bool pedal_burns) {
  const physics::InstrumentPose& pose = input.instruments[1].pose;
  const bool jaw_open = pose.jaw_angle_rad > geometry_.jaw_open_rad;
  const bool closing = right_jaw_was_open_ && !jaw_open;
  right_jaw_was_open_ = jaw_open;
  switch (input.right_tool) {
    case physics::InstrumentTool::kCauteryHook:
      if (pedal_burns) fat_->Burn(scene.tool_tip(1), geometry_.hook_burn_radius_m, geometry_.hook_power_W, h_s_);
      return;
    case physics::InstrumentTool::kClipApplier:
    case physics::InstrumentTool::kScissors: {
      if (!closing) return;
      const auto jaws = RightJawSegment(scene, pose);
      const auto hit = tubes_.NearestToSegment(jaws[0], jaws[1], geometry_.jaw_capture_gap_m);
      if (!hit) return;
      const bool clip = input.right_tool == physics::InstrumentTool::kClipApplier;
      const auto result = clip ? tubes_.PlaceClip(hit->tube, hit->s_m) : tubes_.Cut(hit->tube, hit->s_m);
      if (result != physics::calot::ToolActionResult::kDone) return;
      calot::CalotEvent event;
      event.kind = clip ? calot::CalotEventKind::kClip : calot::CalotEventKind::kCut;
      event.structure = hit->tube;
      event.s = std::clamp(hit->s_m / tubes_.TubeLength_m(hit->tube), 0.0, 1.0);
      event.time_s = scene.time_s();
      pending_events_.push_back(event);
      return;
    }
    case physics::InstrumentTool::kGrasper:
      return;
  }
}

double CalotTriangleStep::SeenFraction(const physics::DissectionScene& scene, int tube) {
  if (steps_ % geometry_.visibility_period_steps != 1 && geometry_.visibility_period_steps > 1)
    return seen_fraction_[static_cast<std::size_t>(tube)];
  if (tube == 0) {  // once per refresh: the organs where they are now
    organs_.UpdateVertices(liver_surface_, scene.liver_positions());
    organs_.UpdateVertices(gallbladder_surface_, scene.gallbladder_surface_positions());
  }
  constexpr int kSamples = 24;
  const CalotCamera& c = setup_.camera;
  const Eigen::Vector3d right = c.forward_W.cross(c.up_W).normalized();
  const double tan_v = std::tan(0.5 * c.vertical_view_angle_rad);
  const double tan_h = c.aspect * tan_v;
  const double length_m = tubes_.TubeLength_m(tube);
  int seen = 0;
  for (int k = 0; k < kSamples; ++k) {
    const Eigen::Vector3d p = tubes_.PositionAt(tube, length_m * (k + 0.5) / kSamples);
    const Eigen::Vector3d d = p - c.p_Eye_W_m;
    const double depth = d.dot(c.forward_W);
    if (depth <= 0 || std::abs(d.dot(c.up_W)) > tan_v * depth || std::abs(d.dot(right)) > tan_h * depth) continue;
    const double distance_m = d.norm();
    const auto hit = organs_.FirstHit(physics::ToolSegment{c.p_Eye_W_m, p});
    if (hit && hit->distance < distance_m - geometry_.occlusion_margin_m) continue;  // behind an organ
    ++seen;
  }
  return seen_fraction_[static_cast<std::size_t>(tube)] = static_cast<double>(seen) / kSamples;
}

double CalotTriangleStep::LowerThirdSeparatedFraction(const physics::DissectionScene& scene) const {
  if (lower_third_springs_.empty()) return 0.0;
  const auto& springs = scene.tissue().springs;
  int cut = 0;
  for (const int s : lower_third_springs_) cut += springs[static_cast<std::size_t>(s)].alive ? 0 : 1;
  return static_cast<double>(cut) / static_cast<double>(lower_third_springs_.size());
}

void CalotTriangleStep::FillSnapshot(const physics::DissectionScene& scene) {
  snapshot_.time_s = scene.time_s();
  snapshot_.structures.resize(tubes_.description().tubes.size());
  const auto leaks = tubes_.Leaks();
  for (int t = 0; t < tubes_.num_tubes(); ++t) {
    const auto& description = tubes_.description().tubes[static_cast<std::size_t>(t)];
    calot::StructureState& state = snapshot_.structures[static_cast<std::size_t>(t)];
    const double length_m = tubes_.TubeLength_m(t);
    state.kind = StructureKindOf(description.kind);
    state.name = description.name;
    state.planned_cut_s = setup_.triangle.tubes[static_cast<std::size_t>(t)].planned_cut_s;
    state.clips_s.clear();
    for (const auto& clip : tubes_.clips())
      if (clip.tube == t) state.clips_s.push_back(std::clamp(clip.s_m / length_m, 0.0, 1.0));
    state.cuts_s.clear();
    for (const auto& cut : tubes_.cuts())
      if (cut.tube == t) state.cuts_s.push_back(std::clamp(cut.s_m / length_m, 0.0, 1.0));
    state.bleeding = state.bile_leaking = false;
    for (const auto& leak : leaks) {
      if (leak.tube != t) continue;
      (leak.fluid == physics::calot::Fluid::kBlood ? state.bleeding : state.bile_leaking) = true;
    }
    state.enters_gallbladder = calot::IsCysticStructure(state.kind);
    state.visible_fraction = std::clamp(fat_->UncoveredFraction(t) * SeenFraction(scene, t), 0.0, 1.0);
  }
  snapshot_.fat_removed_fraction = std::clamp(fat_->TriangleClearedFraction(), 0.0, 1.0);
  snapshot_.lower_third_separated_fraction = LowerThirdSeparatedFraction(scene);
  snapshot_.events = std::move(pending_events_);
  pending_events_.clear();
}

}  // namespace vesica::app
