#include "app/replay/scripted_surgeon.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "app/replay/script_geometry.h"
#include "physics/collision/surface_ray_caster.h"
#include "physics/tissue/connective_tissue.h"

namespace vesica::app {

namespace {
using Vec3 = Eigen::Vector3d;

// Taking hold of the gallbladder at one surface vertex: move to just outside it, keep still for
// kDwell, close the jaws, keep still for kDwell, then check the hold. Every event sits between
// stills, so a replay that interpolates the recording's frames reproduces it.
struct GraspApproach {
  double arrived_at = -1;
  double offset_m = 0.001;  // how far outside the surface the jaws close; deeper after each miss

  void Restart() { arrived_at = -1, offset_m = 0.001; }

  /// One step toward `vertex`; true once the closed jaws hold the gallbladder.
  bool Step(double t, const physics::DissectionScene& scene, const physics::TriangleMesh& surface, int vertex,
            double max_step, Vec3& tip, double& jaw) {
    constexpr double kDwell = 0.1;
    if (arrived_at < 0) {
      const physics::Vertices x = scene.gallbladder_surface_positions();
      const physics::Vertices n = VertexNormals(surface, x);
      const Vec3 target = x.row(vertex).transpose() + offset_m * n.row(vertex).transpose();
      tip = MoveToward(tip, target, max_step);
      if ((tip - target).norm() < 1e-9) arrived_at = t;
    } else if (jaw > 0.0 && t - arrived_at >= kDwell) {
      jaw = 0.0;
    } else if (jaw == 0.0 && t - arrived_at >= 2 * kDwell) {
      arrived_at = -1;
      if (scene.grasp().state() == physics::GraspStateMachine::State::kHolding) return true;
      jaw = 0.5;
      offset_m -= 0.0005;
    }
    return false;
  }
};

// One physics step with both tips where the plan puts them; the input goes into `frames`.
SessionStepReport StepBoth(DissectionSession& session, const physics::InstrumentMount& grasper, const Vec3& grasp_tip,
                           double jaw, const physics::InstrumentMount& hook, const Vec3& hook_tip, bool pedal,
                           std::vector<device::InputFrame>& frames) {
  device::InputFrame f;
  f.time_s = session.time_s();
  f.instruments[0].pose = PoseFor(grasper, grasp_tip, jaw);
  f.instruments[1].pose = PoseFor(hook, hook_tip, 0.0);
  f.instruments[1].pedal = pedal;
  const SessionStepReport r = session.Step(f);
  frames.push_back(f);
  return r;
}
}  // namespace

namespace {
std::vector<device::InputFrame> RunFundusPlan(DissectionSession& session, const ScriptedSurgeonSettings& st) {
  const physics::DissectionModel& model = session.scene().model();
  const physics::DissectionScene& scene = session.scene();
  const double h = model.settings.time_step_s;
  const double max_step = st.tip_speed_m_per_s * h;
  const physics::InstrumentMount& grasper = model.instruments[0];
  const physics::InstrumentMount& hook = model.instruments[1];
  const Vec3 away = -model.toward_liver;

  // The fundus: farthest from the springs' centroid among surface points facing the grasper.
  const physics::TriangleMesh& surface = model.gallbladder_boundary.surface;
  Vec3 bed = Vec3::Zero();
  for (const physics::TissueSpring& s : model.tissue.springs)
    bed += model.gallbladder->rest_mesh.vertices.row(s.gallbladder_vertex).transpose();
  bed /= static_cast<double>(model.tissue.springs.size());
  const physics::Vertices rest_normals = VertexNormals(surface, surface.vertices);
  int fundus = -1;
  double best = -1;
  for (int v = 0; v < surface.num_vertices(); ++v) {
    const Vec3 p = surface.vertices.row(v).transpose();
    const Vec3 to_trocar = (grasper.p_RemoteCentre_W - p).normalized();
    if (rest_normals.row(v).dot(to_trocar) < 0.5) continue;
    const double d = (p - bed).norm();
    if (d > best) best = d, fundus = v;
  }
  if (fundus < 0) throw std::runtime_error("scripted dissection: no gallbladder surface faces the grasper's trocar");

  // Springs from the fundus end to the neck.
  std::vector<int> order(model.tissue.springs.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int>(i);
  const Vec3 fundus_rest = surface.vertices.row(fundus).transpose();
  auto rest_end = [&](int s) -> Vec3 {
    return model.gallbladder->rest_mesh.vertices.row(model.tissue.springs[static_cast<size_t>(s)].gallbladder_vertex);
  };
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    return (rest_end(a) - fundus_rest).norm() < (rest_end(b) - fundus_rest).norm();
  });
  std::vector<double> gave_up_at(order.size(), -1.0);

  enum class Phase { kApproach, kRetract, kDissect, kRelease, kDone } phase = Phase::kApproach;
  Vec3 grasp_tip = grasper.p_RemoteCentre_W + 0.05 * grasper.reference_direction_W;
  const Vec3 hook_home = hook.p_RemoteCentre_W + 0.05 * hook.reference_direction_W;
  Vec3 hook_tip = hook_home;
  Vec3 retract_origin = Vec3::Zero();
  GraspApproach approach;
  double jaw = 0.5, phase_start = 0, spring_start = 0;
  int target_spring = -1;
  std::vector<device::InputFrame> frames;
  const int total = static_cast<int>(model.tissue.springs.size());

  while (phase != Phase::kDone && session.time_s() < st.max_session_s) {
    const double t = session.time_s();
    bool pedal = false;
    switch (phase) {
      case Phase::kApproach:
        if (approach.Step(t, scene, surface, fundus, max_step, grasp_tip, jaw)) {
          phase = Phase::kRetract;
          retract_origin = grasp_tip;
          phase_start = t;
        }
        break;
      case Phase::kRetract:
      case Phase::kDissect: {
        if (scene.grasp().state() != physics::GraspStateMachine::State::kHolding) {  // slipped: take it again
          phase = Phase::kApproach;
          jaw = 0.5;
          approach.Restart();
          break;
        }
        const double cut = static_cast<double>(total - scene.tissue().num_alive()) / total;
        grasp_tip = MoveToward(grasp_tip, retract_origin + (st.retraction_m + st.retraction_gain_m * cut) * away,
                               max_step * 0.5);
        if (phase == Phase::kRetract) {
          if (t - phase_start > 1.0) phase = Phase::kDissect;
          break;
        }
        if (scene.gallbladder_free()) {
          phase = Phase::kRelease;
          phase_start = t;
          break;
        }
        if (target_spring < 0 || !scene.tissue().springs[static_cast<size_t>(target_spring)].alive) {
          target_spring = -1;
          for (size_t k = 0; k < order.size() && target_spring < 0; ++k) {
            const int s = order[k];
            if (scene.tissue().springs[static_cast<size_t>(s)].alive &&
                (gave_up_at[static_cast<size_t>(s)] < 0 || t - gave_up_at[static_cast<size_t>(s)] > 5.0))
              target_spring = s;
          }
          spring_start = t;
          if (target_spring < 0) break;  // all remaining ones given up on recently: wait
        }
        const physics::Vertices m = scene.membrane_points();
        const Vec3 target = 0.5 * (m.row(2 * target_spring) + m.row(2 * target_spring + 1)).transpose();
        hook_tip = MoveToward(hook_tip, target, max_step);
        pedal = (hook_tip - target).norm() < st.burn_distance_m;
        if (t - spring_start > st.spring_timeout_s) {
          gave_up_at[static_cast<size_t>(target_spring)] = t;
          target_spring = -1;
        }
        break;
      }
      case Phase::kRelease: {
        jaw = 0.5;
        hook_tip = MoveToward(hook_tip, hook_home, max_step);
        if (t - phase_start > st.release_hold_s) {
          grasp_tip = MoveToward(grasp_tip, grasper.p_RemoteCentre_W + 0.05 * grasper.reference_direction_W, max_step);
          if (t - phase_start > st.release_hold_s + 1.0) phase = Phase::kDone;
        }
        break;
      }
      case Phase::kDone:
        break;
    }
    const SessionStepReport r = StepBoth(session, grasper, grasp_tip, jaw, hook, hook_tip, pedal, frames);
    if (st.on_step) st.on_step(session, r);
    if (st.log_progress && session.scene().steps() % static_cast<long>(1.0 / h + 0.5) == 0) {
      std::fprintf(
          stderr,
          "t %6.2f s phase %d springs alive %3d grasp %d target %3d hook-target %.4f m f %.2f/%.2f N E %.3g J\n",
          session.time_s(), static_cast<int>(phase), scene.tissue().num_alive(),
          static_cast<int>(scene.grasp().state()), target_spring,
          target_spring >= 0 ? (hook_tip - 0.5 * (scene.membrane_points().row(2 * target_spring) +
                                                  scene.membrane_points().row(2 * target_spring + 1))
                                                     .transpose())
                                   .norm()
                             : -1.0,
          r.physics.tool_force_N[0].norm(), r.physics.tool_force_N[1].norm(), scene.Energy());
    }
  }
  return frames;
}

// The membrane triangles still attached (both springs alive), with their centroids now.
struct MembraneTarget {
  int triangle = -1;
  Vec3 centroid = Vec3::Zero();
};
std::vector<MembraneTarget> AttachedMembrane(const physics::DissectionScene& scene) {
  const physics::Vertices points = scene.membrane_points();
  const physics::TissueMembrane& membrane = scene.tissue().membrane;
  std::vector<MembraneTarget> out;
  for (Eigen::Index f = 0; f < membrane.triangles.rows(); ++f) {
    if (!scene.tissue().springs[static_cast<size_t>(membrane.springs(f, 0))].alive ||
        !scene.tissue().springs[static_cast<size_t>(membrane.springs(f, 1))].alive)
      continue;
    const Vec3 c = (points.row(membrane.triangles(f, 0)) + points.row(membrane.triangles(f, 1)) +
                    points.row(membrane.triangles(f, 2)))
                       .transpose() /
                   3.0;
    out.push_back({static_cast<int>(f), c});
  }
  return out;
}

// The organs as they are now, for line-of-sight tests.
class OrganSight {
 public:
  explicit OrganSight(const physics::DissectionScene& scene) : scene_(scene) {
    physics::TriangleMesh gallbladder = scene.model().gallbladder_boundary.surface;
    liver_ = caster_.AddSurface(scene.model().liver->rest_surface);
    gallbladder_ = caster_.AddSurface(gallbladder);
  }
  void Update() {
    caster_.UpdateVertices(liver_, scene_.liver_positions());
    caster_.UpdateVertices(gallbladder_, scene_.gallbladder_surface_positions());
  }
  /// No organ surface crosses the segment from `from` to within `tolerance_m` of `to`.
  bool Clear(const Vec3& from, const Vec3& to, double tolerance_m) const {
    const double length = (to - from).norm();
    if (length <= tolerance_m) return true;
    const Vec3 end = from + (to - from) * ((length - tolerance_m) / length);
    return !caster_.FirstHit(physics::ToolSegment{from, end}).has_value();
  }

 private:
  const physics::DissectionScene& scene_;
  physics::SurfaceRayCaster caster_;
  int liver_ = -1, gallbladder_ = -1;
};

// The fraction of the attached membrane's area whose centroids `eye` sees (the measure of
// tests/field/committed_dissection_sight_test.cpp); 1 when none is attached.
double MembraneInSight(const physics::DissectionScene& scene, const OrganSight& sight, const Vec3& eye) {
  const physics::Vertices points = scene.membrane_points();
  const physics::TissueMembrane& membrane = scene.tissue().membrane;
  double area = 0, seen = 0;
  for (const MembraneTarget& m : AttachedMembrane(scene)) {
    const Vec3 a = points.row(membrane.triangles(m.triangle, 0)), b = points.row(membrane.triangles(m.triangle, 1)),
               c = points.row(membrane.triangles(m.triangle, 2));
    const double a_m2 = 0.5 * (b - a).cross(c - a).norm();
    area += a_m2;
    if (sight.Clear(eye, m.centroid, 0.0005)) seen += a_m2;
  }
  return area > 0 ? seen / area : 1.0;
}

// Whether the grasper's jaws can take the gallbladder's surface point `p` (outward normal `n`)
// from its port: the surface faces the port within 75 degrees, along a straight path clear of the
// organs. (Within 60 degrees, the rule before, left the French position's flank port nothing near
// Hartmann's pouch: the re-grasps went to the fundus, far from the springs left.)
bool GrasperTakes(const OrganSight& sight, const Vec3& port, const Vec3& p, const Vec3& n) {
  const double facing = n.dot((port - p).normalized());
  return facing >= std::cos(75.0 * std::numbers::pi / 180) && sight.Clear(port, p + 0.002 * n, 0.0);
}

// Whether the hook reaches `past_m` beyond the triangle's centroid along a straight shaft from
// its port without crossing an organ.
bool HookReaches(const OrganSight& sight, const Vec3& port, const MembraneTarget& m, double past_m) {
  return sight.Clear(port, m.centroid + past_m * (m.centroid - port).normalized(), 0.0);
}

// The fraction of the attached membrane's triangles the hook reaches (1 when none is attached).
double HookReachFraction(const physics::DissectionScene& scene, const OrganSight& sight, const Vec3& port,
                         double past_m) {
  const std::vector<MembraneTarget> attached = AttachedMembrane(scene);
  const auto reached = std::count_if(attached.begin(), attached.end(),
                                     [&](const MembraneTarget& m) { return HookReaches(sight, port, m, past_m); });
  return attached.empty() ? 1.0 : static_cast<double>(reached) / static_cast<double>(attached.size());
}

std::vector<device::InputFrame> RunPouchPlan(DissectionSession& session, const ScriptedSurgeonSettings& st) {
  const physics::DissectionModel& model = session.scene().model();
  const physics::DissectionScene& scene = session.scene();
  const double h = model.settings.time_step_s;
  const double max_step = st.tip_speed_m_per_s * h;
  const physics::InstrumentMount& grasper = model.instruments[0];
  const physics::InstrumentMount& hook = model.instruments[1];

  // The neck: the gallbladder node farthest from the assistant's hold on the fundus. Hartmann's
  // pouch: the stretch from a sixth to a third of the way from the neck to the fundus.
  const physics::Vertices& rest = model.gallbladder->rest_mesh.vertices;
  Vec3 fundus = Vec3::Zero();
  for (int node : model.retraction.nodes) fundus += rest.row(node).transpose();
  fundus /= static_cast<double>(model.retraction.nodes.size());
  Vec3 neck = fundus;
  for (Eigen::Index v = 0; v < rest.rows(); ++v)
    if ((rest.row(v).transpose() - fundus).norm() > (neck - fundus).norm()) neck = rest.row(v).transpose();
  auto along_gallbladder = [&](const Vec3& p) { return (p - neck).dot(fundus - neck) / (fundus - neck).squaredNorm(); };
  const physics::TriangleMesh& surface = model.gallbladder_boundary.surface;
  const physics::Vertices rest_normals = VertexNormals(surface, surface.vertices);
  OrganSight sight(scene);
  sight.Update();
  // The grasper takes the pouch where its jaws come at it most squarely along a path from its
  // port that crosses neither organ (the pouch's side facing the port is often seen edge-on from
  // it: the port lies toward the liver's edge, above the gallbladder).
  int pouch = -1;
  double best_facing = 0;
  for (int v = 0; v < surface.num_vertices(); ++v) {
    const Vec3 p = surface.vertices.row(v).transpose(), n = rest_normals.row(v).transpose();
    const double along = along_gallbladder(p);
    if (along < 1.0 / 6 || along > 1.0 / 3) continue;
    const double facing = n.dot((grasper.p_RemoteCentre_W - p).normalized());
    if (facing <= best_facing || !sight.Clear(grasper.p_RemoteCentre_W, p + 0.002 * n, 0.0)) continue;
    best_facing = facing;
    pouch = v;
  }
  if (pouch < 0)
    throw std::runtime_error("scripted dissection: the grasper's port reaches no side of Hartmann's pouch");
  // The traction's direction: laterally, away from the fossa's rim the springs were grown
  // toward, which opens the slot beside the gallbladder to the scope. (Lifting toward the scope as
  // well turned the membrane edge-on: 79 % of it in sight at worst, against 90 %.) Where the
  // hook comes at the slot across the fossa's medial rim (the French position's left
  // hypochondrium), the pull turns `tilt_rad` caudally, the inferolateral traction on Hartmann's
  // pouch of the textbook, which lifts the gallbladder's side of the membrane out of the fossa
  // above the rim: from the start where the hook's port reaches little of the membrane at rest
  // (below), further, step by step, while it reaches none of what is left.
  double tilt_rad = 0;
  auto traction = [&]() -> Vec3 {
    const Vec3 lateral = -model.toward_liver;
    if (tilt_rad == 0) return lateral;
    const Vec3 caudal_W(0, 0, -1);  // the patient frame's z is cranial
    const Vec3 caudal = (caudal_W - caudal_W.dot(lateral) * lateral).normalized();
    return std::cos(tilt_rad) * lateral + std::sin(tilt_rad) * caudal;
  };
  constexpr double kRadPerDeg = std::numbers::pi / 180;
  const double tilt_step_rad = st.traction_tilt_step_deg * kRadPerDeg;
  const double max_tilt_rad = st.max_traction_tilt_deg * kRadPerDeg;
  int grip = pouch;
  if (st.log_progress)
    std::fprintf(stderr,
                 "grasping Hartmann's pouch at vertex %d, %.2f of the way from the neck to the fundus, facing the port "
                 "at %.0f degrees\n",
                 pouch, along_gallbladder(surface.vertices.row(pouch).transpose()),
                 std::acos(best_facing) * 180 / std::numbers::pi);
  // The hook's burns start kShort before a target and end kPast beyond it (HookMove below).
  constexpr double kShort = 0.005, kPast = 0.002, kBurnSpeed = 0.01, kTension_N = 1.0;
  // How much of the membrane the hook's port reaches in a straight line before any traction: from
  // the epigastric port about half (91 of 178 triangles); from the French position's left
  // hypochondrium 13, the fossa's medial rim lying between. Where it is under
  // hidden_slot_reach_fraction, the pull is inferolateral and longer from the start (lateral
  // alone, 1.2 to 2 cm, left the membrane under the rim: 17 of 41 springs cut in 120 s).
  const double reach_at_rest = HookReachFraction(scene, sight, hook.p_RemoteCentre_W, kPast);
  const bool slot_hidden_from_hook = reach_at_rest < st.hidden_slot_reach_fraction;
  const double retraction_m = slot_hidden_from_hook ? st.hidden_slot_retraction_m : st.retraction_m;
  if (slot_hidden_from_hook) tilt_rad = st.hidden_slot_tilt_deg * kRadPerDeg;
  if (st.log_progress)
    std::fprintf(stderr,
                 "the hook's port reaches %.0f %% of the membrane at rest: traction %.0f degrees caudal of lateral\n",
                 100 * reach_at_rest, tilt_rad / kRadPerDeg);
  Vec3 lateral = traction();
  double stuck_since = -1;

  enum class Phase { kSettle, kApproach, kRetract, kDissect, kRelease, kDone } phase = Phase::kSettle;
  // The hook's moves on one target: to 5 mm short of it along its shaft, then with the pedal
  // down through it to 2 mm past, then back to where it started burning.
  enum class HookMove { kChoose, kToStart, kBurn, kBack } hook_move = HookMove::kChoose;
  double pull_m = 0;
  Vec3 grasp_tip = grasper.p_RemoteCentre_W + 0.05 * grasper.reference_direction_W;
  const Vec3 hook_home = hook.p_RemoteCentre_W + 0.05 * hook.reference_direction_W;
  Vec3 hook_tip = hook_home, burn_from = hook_home, burn_to = hook_home;
  Vec3 retract_origin = Vec3::Zero();
  GraspApproach approach;
  double jaw = 0.5, phase_start = 0, still_since = -1;
  int target_triangle = -1, tries_on_target = 0;
  std::vector<double> gave_up_at(static_cast<size_t>(scene.tissue().membrane.triangles.rows()), -1.0);
  std::vector<device::InputFrame> frames;
  const int total = static_cast<int>(model.tissue.springs.size());

  while (phase != Phase::kDone && session.time_s() < st.max_session_s) {
    const double t = session.time_s();
    bool pedal = false;
    switch (phase) {
      case Phase::kSettle:
        if (t >= 1.0) phase = Phase::kApproach;  // the organs settle under the assistant's hold
        break;
      case Phase::kApproach:
        if (approach.Step(t, scene, surface, grip, max_step, grasp_tip, jaw)) {
          phase = Phase::kRetract;
          retract_origin = grasp_tip;
          pull_m = 0;
          phase_start = t;
        }
        break;
      case Phase::kRetract:
      case Phase::kDissect: {
        if (scene.grasp().state() != physics::GraspStateMachine::State::kHolding) {  // slipped: take it again
          phase = Phase::kApproach;
          jaw = 0.5;
          approach.Restart();
          hook_move = HookMove::kChoose;
          break;
        }
        // Traction as a surgeon keeps it: further as the springs go, eased off while the pull on
        // the jaws is above kTension (a harder pull tears the grasp loose).
        const double cut = static_cast<double>(total - scene.tissue().num_alive()) / total;
        const double grasp_force_N = scene.haptic_frame(0).f_Tool_W.norm();
        if (grasp_force_N > kTension_N)
          pull_m = std::max(0.0, pull_m - 0.5 * max_step);
        else if (pull_m < retraction_m + st.retraction_gain_m * cut)
          pull_m += 0.5 * max_step;
        grasp_tip = MoveToward(grasp_tip, retract_origin + pull_m * lateral, max_step);
        if (phase == Phase::kRetract) {
          if (t - phase_start > 1.0) phase = Phase::kDissect;
          break;
        }
        if (scene.gallbladder_free()) {
          phase = Phase::kRelease;
          phase_start = t;
          break;
        }
        switch (hook_move) {
          case HookMove::kChoose: {
            // From the neck up: the attached triangle nearest the neck that the hook reaches
            // without crossing an organ and the scope sees.
            sight.Update();
            target_triangle = -1;
            double best = std::numeric_limits<double>::infinity();
            for (const MembraneTarget& m : AttachedMembrane(scene)) {
              if (gave_up_at[static_cast<size_t>(m.triangle)] >= 0 &&
                  t - gave_up_at[static_cast<size_t>(m.triangle)] < 5)
                continue;
              const double d = (m.centroid - neck).norm();
              if (d >= best) continue;
              // The burn's whole path, to 2 mm past the membrane, clear of the organs from the
              // hook's port and, where the scope is given, in its sight.
              const Vec3 along = (m.centroid - hook.p_RemoteCentre_W).normalized();
              const Vec3 from = m.centroid - kShort * along, to = m.centroid + kPast * along;
              if (!sight.Clear(hook.p_RemoteCentre_W, to, 0.0)) continue;
              if (st.scope_eye_W &&
                  (!sight.Clear(*st.scope_eye_W, to, 0.0) || !sight.Clear(*st.scope_eye_W, from, 0.0)))
                continue;
              best = d;
              target_triangle = m.triangle;
              burn_from = from;
              burn_to = to;
            }
            if (target_triangle >= 0) {
              hook_move = HookMove::kToStart;
              still_since = -1;
              stuck_since = -1;
            } else if (stuck_since < 0) {
              stuck_since = t;
            } else if (t - stuck_since > 1.0 && tilt_rad + 1e-9 < max_tilt_rad &&
                       HookReachFraction(scene, sight, hook.p_RemoteCentre_W, kPast) == 0) {
              tilt_rad = std::min(max_tilt_rad, tilt_rad + tilt_step_rad);
              lateral = traction();
              stuck_since = -1;
              if (st.log_progress)
                std::fprintf(stderr, "  traction tilted %.0f degrees caudally (t %.2f s)\n",
                             tilt_rad * 180 / std::numbers::pi, t);
            } else if (t - stuck_since > 1.0) {
              // Nothing left that both the hook and the scope reach: let go and take the
              // gallbladder again nearer the springs still holding it, then lift it from there.
              const physics::Vertices x = scene.gallbladder_surface_positions();
              const physics::Vertices gb = scene.gallbladder().CurrentPositions();
              Vec3 holding = Vec3::Zero();
              int alive = 0;
              for (const physics::TissueSpring& spring : scene.tissue().springs)
                if (spring.alive) holding += gb.row(spring.gallbladder_vertex).transpose(), ++alive;
              holding /= std::max(1, alive);
              const physics::Vertices n = VertexNormals(surface, x);
              int best_grip = -1;
              for (int v = 0; v < surface.num_vertices(); ++v) {
                const Vec3 p = x.row(v).transpose();
                if (v == grip || !GrasperTakes(sight, grasper.p_RemoteCentre_W, p, n.row(v).transpose())) continue;
                if (best_grip < 0 || (p - holding).norm() < (x.row(best_grip).transpose() - holding).norm())
                  best_grip = v;
              }
              if (best_grip >= 0) {
                grip = best_grip;
                lateral = traction();
                phase = Phase::kApproach;
                jaw = 0.5;
                approach.Restart();
                hook_move = HookMove::kChoose;
                stuck_since = -1;
                if (st.log_progress) std::fprintf(stderr, "  re-grasp at %d (t %.2f s)\n", grip, t);
              }
            } else if (std::getenv("VESICA_SCRIPT_DEBUG") && scene.steps() % 200 == 0) {
              int n = 0, reach = 0, seen = 0, both = 0;
              for (const MembraneTarget& m : AttachedMembrane(scene)) {
                ++n;
                const Vec3 along = (m.centroid - hook.p_RemoteCentre_W).normalized();
                const Vec3 to = m.centroid + kPast * along;
                const bool r = sight.Clear(hook.p_RemoteCentre_W, to, 0.0);
                const bool v = !st.scope_eye_W || sight.Clear(*st.scope_eye_W, to, 0.0);
                reach += r;
                seen += v;
                both += r && v;
              }
              double lo = 1e9, hi = -1e9;
              for (const physics::TissueSpring& spring : scene.tissue().springs)
                if (spring.alive) {
                  const double a = along_gallbladder(rest.row(spring.gallbladder_vertex).transpose());
                  lo = std::min(lo, a), hi = std::max(hi, a);
                }
              std::fprintf(
                  stderr,
                  "  attached %d, reachable %d, seen %d, both %d; springs left %.2f to %.2f of the way from the "
                  "neck, grip at %.2f\n",
                  n, reach, seen, both, lo, hi, along_gallbladder(surface.vertices.row(grip).transpose()));
            }
            break;
          }
          case HookMove::kToStart:
            hook_tip = MoveToward(hook_tip, burn_from, max_step);
            if ((hook_tip - burn_from).norm() < 1e-9) {
              if (still_since < 0) still_since = t;
              if (t - still_since >= 0.05) hook_move = HookMove::kBurn;
            }
            break;
          case HookMove::kBurn: {
            const physics::TissueMembrane& membrane = scene.tissue().membrane;
            const bool parted =
                !scene.tissue().springs[static_cast<size_t>(membrane.springs(target_triangle, 0))].alive ||
                !scene.tissue().springs[static_cast<size_t>(membrane.springs(target_triangle, 1))].alive;
            // The organs move as the springs go: a surgeon lifts the pedal the moment the tip
            // would pass behind one, or once the membrane there has parted.
            bool hidden = false;
            if (st.scope_eye_W && scene.steps() % 5 == 0) {
              sight.Update();
              hidden = !sight.Clear(*st.scope_eye_W, hook_tip, 0.0) ||
                       !sight.Clear(*st.scope_eye_W, MoveToward(hook_tip, burn_to, 0.001), 0.0);
            }
            if (parted || hidden) {
              hook_move = HookMove::kBack;
              tries_on_target = 0;
              if (hidden && !parted) gave_up_at[static_cast<size_t>(target_triangle)] = t;
              break;
            }
            pedal = true;
            hook_tip = MoveToward(hook_tip, burn_to, kBurnSpeed * h);
            if ((hook_tip - burn_to).norm() < 1e-9) {
              hook_move = HookMove::kBack;
              if (++tries_on_target >= 2) {
                gave_up_at[static_cast<size_t>(target_triangle)] = t;
                tries_on_target = 0;
              }
            }
            break;
          }
          case HookMove::kBack:
            hook_tip = MoveToward(hook_tip, burn_from, max_step);
            if ((hook_tip - burn_from).norm() < 1e-9) hook_move = HookMove::kChoose;
            break;
        }
        break;
      }
      case Phase::kRelease: {
        // The freed gallbladder stays in the jaws for release_hold_s, then they open.
        hook_tip = MoveToward(hook_tip, hook_home, max_step);
        if (t - phase_start > st.release_hold_s) jaw = 0.5;
        if (t - phase_start > st.release_hold_s + 0.5) {
          grasp_tip = MoveToward(grasp_tip, grasper.p_RemoteCentre_W + 0.05 * grasper.reference_direction_W, max_step);
          if (t - phase_start > st.release_hold_s + 2.0) phase = Phase::kDone;
        }
        break;
      }
      case Phase::kDone:
        break;
    }
    const SessionStepReport r = StepBoth(session, grasper, grasp_tip, jaw, hook, hook_tip, pedal, frames);
    if (st.on_step) st.on_step(session, r);
    if (st.log_progress && session.scene().steps() % static_cast<long>(0.5 / h + 0.5) == 0) {
      double in_sight = -1;
      if (st.scope_eye_W) {
        sight.Update();
        in_sight = MembraneInSight(scene, sight, *st.scope_eye_W);
      }
      std::fprintf(stderr,
                   "t %6.2f s phase %d springs alive %3d grasp %d target %4d f %.2f/%.2f N membrane in sight %.1f %%\n",
                   session.time_s(), static_cast<int>(phase), scene.tissue().num_alive(),
                   static_cast<int>(scene.grasp().state()), target_triangle, r.physics.tool_force_N[0].norm(),
                   r.physics.tool_force_N[1].norm(), 100 * in_sight);
    }
  }
  return frames;
}
}  // namespace

std::vector<device::InputFrame> RunScriptedDissection(DissectionSession& session, const ScriptedSurgeonSettings& st) {
  return session.scene().model().retraction.empty() ? RunFundusPlan(session, st) : RunPouchPlan(session, st);
}

}  // namespace vesica::app
