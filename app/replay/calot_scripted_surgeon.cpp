#include "app/replay/calot_scripted_surgeon.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <stdexcept>

#include "app/replay/script_geometry.h"
#include "physics/collision/surface_ray_caster.h"

namespace vesica::app {

namespace {

using Vec3 = Eigen::Vector3d;
using physics::InstrumentTool;
using physics::calot::FatCellState;

constexpr int kCysticDuct = 0, kCysticArtery = 1, kCommonBileDuct = 3;
constexpr double kJawOpen_rad = 0.5;
constexpr double kSpreadClosed_rad = 0.12;  // just open: the jaws straddle a tube instead of pushing it
constexpr double kPi = 3.14159265358979323846;
constexpr double kDwell_s = 0.05;  // still before and after every switch (jaws, pedal, tool)

// The liver and the gallbladder as they are now, for straight paths and lines of sight.
class OrganSight {
 public:
  explicit OrganSight(const physics::DissectionScene& scene) : scene_(scene) {
    liver_ = caster_.AddSurface(scene.model().liver->rest_surface);
    gallbladder_ = caster_.AddSurface(scene.model().gallbladder_boundary.surface);
    Update();
  }
  void Update() {
    caster_.UpdateVertices(liver_, scene_.liver_positions());
    caster_.UpdateVertices(gallbladder_, scene_.gallbladder_surface_positions());
  }
  /// No organ surface crosses the segment from `from` to `to`.
  bool Clear(const Vec3& from, const Vec3& to) const {
    return !caster_.FirstHit(physics::ToolSegment{from, to}).has_value();
  }
  /// No liver surface crosses it (the soft gallbladder gives way to a shaft; the liver does not).
  bool ClearOfLiver(const Vec3& from, const Vec3& to) const {
    return !caster_.FirstHit(liver_, physics::ToolSegment{from, to}).has_value();
  }

 private:
  const physics::DissectionScene& scene_;
  physics::SurfaceRayCaster caster_;
  int liver_ = -1, gallbladder_ = -1;
};

// What the right hand does with its jaws: close the tool across the tube at s (0..1 of its length).
struct JawAction {
  InstrumentTool tool = InstrumentTool::kClipApplier;
  int tube = 0;
  double s = 0.5;
};

class CalotSurgeon {
 public:
  CalotSurgeon(DissectionSession& session, CalotScript script, const CalotSurgeonSettings& settings)
      : session_(session),
        scene_(session.scene()),
        model_(scene_.model()),
        script_(script),
        st_(settings),
        h_(model_.settings.time_step_s),
        max_step_(settings.tip_speed_m_per_s * h_),
        grasper_(model_.instruments[0]),
        right_(model_.instruments[1]),
        sight_(scene_) {
    if (!session.calot_step()) throw std::invalid_argument("scripted Calot dissection: the session has no triangle");
    if (!(st_.tip_speed_m_per_s > 0)) throw std::invalid_argument("scripted Calot dissection: tip_speed_m_per_s <= 0");
    tubes_ = session.calot_tubes();
    fat_ = session.calot_fat();
    grasp_tip_ = grasper_.p_RemoteCentre_W + 0.05 * grasper_.reference_direction_W;
    grasp_home_ = grasp_tip_;
    right_home_ = right_.p_RemoteCentre_W + 0.05 * right_.reference_direction_W;
    right_tip_ = right_home_;
    ChoosePouch();
    give_up_until_s_.assign(fat_->cells().size(), -1.0);
    membrane_give_up_until_s_.assign(static_cast<std::size_t>(model_.tissue.membrane.triangles.rows()), -1.0);
  }

  std::vector<device::InputFrame> Run() {
    while (!done_ && session_.time_s() < st_.max_session_s && !session_.case_ended()) {
      LeftHand();
      RightHand();
      Record();
      if (st_.log_progress && scene_.steps() % static_cast<long>(5.0 / h_ + 0.5) == 0) Log();
    }
    if (st_.log_progress) Log();
    return std::move(frames_);
  }

 private:
  enum class RightPhase { kWait, kLowerThird, kFat, kSpread, kExchange, kJaws, kHome, kDone };
  enum class LeftMode { kHoldPouch, kSpread, kAway };

  // ---- the left hand: take Hartmann's pouch and keep it retracted laterally ----

  // Hartmann's pouch: the surface a sixth to a third of the way from the neck to the fundus that
  // a straight path from the grasper's port, clear of the organs, meets most squarely.
  void ChoosePouch() {
    const physics::Vertices& rest = model_.gallbladder->rest_mesh.vertices;
    const Vec3 neck = tubes_->description().p_Neck_W_m;
    Vec3 fundus = neck;
    if (!model_.retraction.empty()) {
      fundus = Vec3::Zero();
      for (const int node : model_.retraction.nodes) fundus += rest.row(node).transpose();
      fundus /= static_cast<double>(model_.retraction.nodes.size());
    } else {
      for (Eigen::Index v = 0; v < rest.rows(); ++v)
        if ((rest.row(v).transpose() - neck).norm() > (fundus - neck).norm()) fundus = rest.row(v).transpose();
    }
    const physics::TriangleMesh& surface = model_.gallbladder_boundary.surface;
    const physics::Vertices x = scene_.gallbladder_surface_positions();
    const physics::Vertices n = VertexNormals(surface, x);
    double best_facing = 0;
    for (int v = 0; v < surface.num_vertices(); ++v) {
      const Vec3 p = x.row(v).transpose();
      const double along = (p - neck).dot(fundus - neck) / (fundus - neck).squaredNorm();
      if (along < 1.0 / 6 || along > 1.0 / 3) continue;
      const double facing = n.row(v).dot((grasper_.p_RemoteCentre_W - p).normalized());
      if (facing <= best_facing || !sight_.Clear(grasper_.p_RemoteCentre_W, p + 0.002 * n.row(v).transpose())) continue;
      best_facing = facing;
      pouch_vertex_ = v;
    }
    if (pouch_vertex_ < 0)
      throw std::runtime_error("scripted Calot dissection: the grasper's port reaches no side of Hartmann's pouch");
  }

  bool Holding() const { return scene_.grasp().state() == physics::GraspStateMachine::State::kHolding; }

  // Move to 1 mm outside the pouch, still, close, still, check; deeper by 0.5 mm after a miss.
  // Once held: traction laterally (away from the fossa's rim), eased off above the force limit.
  void LeftHand() {
    const double t = session_.time_s();
    if (t < st_.settle_s) return;
    if (left_mode_ == LeftMode::kSpread) {
      Spread();
      return;
    }
    if (left_mode_ == LeftMode::kAway) {
      left_jaw_ = kSpreadClosed_rad;
      grasp_tip_ = MoveToward(grasp_tip_, grasp_home_, max_step_);
      return;
    }
    if (holding_ && !Holding()) {  // slipped: take it again
      holding_ = false;
      left_jaw_ = kJawOpen_rad;
      arrived_at_ = -1;
      grasp_offset_m_ = 0.001;
    }
    if (!holding_) {
      if (arrived_at_ < 0) {
        const physics::Vertices x = scene_.gallbladder_surface_positions();
        const physics::Vertices n = VertexNormals(model_.gallbladder_boundary.surface, x);
        const Vec3 target = x.row(pouch_vertex_).transpose() + grasp_offset_m_ * n.row(pouch_vertex_).transpose();
        grasp_tip_ = MoveToward(grasp_tip_, target, max_step_);
        if ((grasp_tip_ - target).norm() < 1e-9) arrived_at_ = t;
      } else if (left_jaw_ > 0 && t - arrived_at_ >= 2 * kDwell_s) {
        left_jaw_ = 0;
      } else if (left_jaw_ == 0 && t - arrived_at_ >= 4 * kDwell_s) {
        arrived_at_ = -1;
        if (Holding()) {
          holding_ = true;
          held_since_ = t;
          retract_origin_ = grasp_tip_;
          pull_m_ = 0;
        } else {
          left_jaw_ = kJawOpen_rad;
          grasp_offset_m_ -= 0.0005;
        }
      }
      return;
    }
    const int total = static_cast<int>(model_.tissue.springs.size());
    const double cut = total > 0 ? static_cast<double>(total - scene_.tissue().num_alive()) / total : 0.0;
    if (scene_.haptic_frame(0).f_Tool_W.norm() > st_.max_grasp_force_N)
      pull_m_ = std::max(0.0, pull_m_ - 0.5 * max_step_);
    else if (pull_m_ < st_.retraction_m + st_.retraction_gain_m * cut)
      pull_m_ += 0.5 * max_step_;
    grasp_tip_ = MoveToward(grasp_tip_, retract_origin_ - pull_m_ * model_.toward_liver, max_step_);
  }

  // ---- the right hand ----

  void RightHand() {
    const double t = session_.time_s();
    pedal_ = false;
    switch (phase_) {
      case RightPhase::kWait:
        if (holding_ && t - held_since_ >= 1.0) {
          PlanJawActions();
          if (script_ == CalotScript::kCorrectDissection)
            Enter(RightPhase::kLowerThird);
          else
            Enter(RightPhase::kExchange);
        }
        break;
      case RightPhase::kLowerThird:
        if (session_.calot_metrics()->LatestAssessment().lower_third_separated) {
          Enter(RightPhase::kFat);
          break;
        }
        BurnMembraneNearNeck();
        break;
      case RightPhase::kFat:
        if (session_.calot_metrics()->CriticalViewTime()) {
          Enter(RightPhase::kExchange);
          break;
        }
        if (!st_.hook_burns_fat) {
          Enter(RightPhase::kSpread);
          break;
        }
        BurnFat();
        break;
      case RightPhase::kSpread:
        // The hook waits at home while the grasper lets go of the pouch and spreads the fat.
        right_tip_ = MoveToward(right_tip_, right_home_, max_step_);
        if (left_mode_ == LeftMode::kHoldPouch && t - phase_start_ >= kDwell_s) {
          left_mode_ = LeftMode::kSpread;
          left_jaw_ = kSpreadClosed_rad;
          spread_ = SpreadMove{};
        }
        if (session_.calot_metrics()->CriticalViewTime()) {
          left_mode_ = LeftMode::kAway;
          Enter(RightPhase::kExchange);
        }
        if (spread_exhausted_) {
          if (st_.log_progress) std::fprintf(stderr, "no fat left to spread, and no critical view\n");
          left_mode_ = LeftMode::kAway;
          Enter(RightPhase::kHome);
        }
        break;
      case RightPhase::kExchange:
        // Still, the new tool in, still (the jaws come open: they close across a tube to act).
        if (t - phase_start_ >= kDwell_s && right_tool_ != actions_[next_action_].tool) {
          right_tool_ = actions_[next_action_].tool;
          right_jaw_ = kJawOpen_rad;
        }
        if (t - phase_start_ >= 2 * kDwell_s) Enter(RightPhase::kJaws);
        break;
      case RightPhase::kJaws:
        JawStep();
        break;
      case RightPhase::kHome:
        right_tip_ = MoveToward(right_tip_, right_home_, max_step_);
        if (t - phase_start_ > 0.5) Enter(RightPhase::kDone);
        break;
      case RightPhase::kDone:
        done_ = true;
        break;
    }
  }

  void Enter(RightPhase phase) {
    phase_ = phase;
    phase_start_ = session_.time_s();
    burn_ = BurnMove{};
    jaw_step_ = JawStage::kApproach;
  }

  // The membrane of the connective tissue from the neck up: the attached triangle nearest the
  // neck that the hook reaches from its port and the scope sees, burnt through along the shaft
  // (5 mm short of it to 2 mm past, pedal down at 10 mm/s), twice at most, then left for 5 s.
  void BurnMembraneNearNeck() {
    constexpr double kShort = 0.005, kPast = 0.002, kBurnSpeed_m_per_s = 0.01;
    const double t = session_.time_s();
    const physics::TissueMembrane& membrane = scene_.tissue().membrane;
    const auto attached = [&](int f) {
      return scene_.tissue().springs[static_cast<std::size_t>(membrane.springs(f, 0))].alive &&
             scene_.tissue().springs[static_cast<std::size_t>(membrane.springs(f, 1))].alive;
    };
    switch (burn_.stage) {
      case BurnStage::kChoose: {
        sight_.Update();
        const physics::Vertices points = scene_.membrane_points();
        const Vec3 neck = session_.calot_step()->neck_W_m();
        double best = std::numeric_limits<double>::infinity();
        burn_.target = -1;
        for (Eigen::Index f = 0; f < membrane.triangles.rows(); ++f) {
          if (!attached(static_cast<int>(f)) || membrane_give_up_until_s_[static_cast<std::size_t>(f)] > t) continue;
          const Vec3 c = (points.row(membrane.triangles(f, 0)) + points.row(membrane.triangles(f, 1)) +
                          points.row(membrane.triangles(f, 2)))
                             .transpose() /
                         3.0;
          if ((c - neck).norm() >= best) continue;
          const Vec3 along = (c - right_.p_RemoteCentre_W).normalized();
          const Vec3 from = c - kShort * along, to = c + kPast * along;
          if (!sight_.Clear(right_.p_RemoteCentre_W, to)) continue;
          if (st_.scope_eye_W && (!sight_.Clear(*st_.scope_eye_W, to) || !sight_.Clear(*st_.scope_eye_W, from)))
            continue;
          best = (c - neck).norm();
          burn_.target = static_cast<int>(f);
          burn_.from = from;
          burn_.to = to;
        }
        if (burn_.target >= 0) burn_.stage = BurnStage::kToStart, burn_.since = -1;
        break;
      }
      case BurnStage::kToStart:
        right_tip_ = MoveToward(right_tip_, burn_.from, max_step_);
        if ((right_tip_ - burn_.from).norm() < 1e-9) {
          if (burn_.since < 0) burn_.since = t;
          if (t - burn_.since >= kDwell_s) burn_.stage = BurnStage::kBurn;
        }
        break;
      case BurnStage::kBurn:
        if (!attached(burn_.target)) {
          burn_.stage = BurnStage::kBack;
          burn_.tries = 0;
          break;
        }
        pedal_ = true;
        right_tip_ = MoveToward(right_tip_, burn_.to, kBurnSpeed_m_per_s * h_);
        if ((right_tip_ - burn_.to).norm() < 1e-9) {
          burn_.stage = BurnStage::kBack;
          if (++burn_.tries >= 2) {
            membrane_give_up_until_s_[static_cast<std::size_t>(burn_.target)] = t + 5.0;
            burn_.tries = 0;
          }
        }
        break;
      case BurnStage::kBack:
        right_tip_ = MoveToward(right_tip_, burn_.from, max_step_);
        if ((right_tip_ - burn_.from).norm() < 1e-9) burn_.stage = BurnStage::kChoose;
        break;
    }
  }

  // The nearest centreline point of any tube to p: its distance and the tube's outer radius.
  struct NearestTube {
    Vec3 p_W_m = Vec3::Zero();
    double distance_m = std::numeric_limits<double>::infinity();
    double radius_m = 0;
  };
  NearestTube NearestTubeTo(const Vec3& p, int only_tube = -1) const {
    NearestTube nearest;
    for (int tube = 0; tube < tubes_->num_tubes(); ++tube) {
      if (only_tube >= 0 && tube != only_tube) continue;
      const double length_m = tubes_->TubeLength_m(tube);
      const int samples = std::max(2, static_cast<int>(length_m / 0.0005) + 1);
      for (int k = 0; k < samples; ++k) {
        const Vec3 q = tubes_->PositionAt(tube, length_m * k / (samples - 1));
        const double d = (q - p).norm();
        if (d < nearest.distance_m)
          nearest = {q, d, tubes_->description().tubes[static_cast<std::size_t>(tube)].material.outer_radius_m};
      }
    }
    return nearest;
  }

  // Where the hook's tip burns cell c from: at the cell, or beside it away from the nearest tube
  // when the tip there would push that tube aside (the tube and its sleeve would slide away).
  Vec3 BurnPointFor(int cell) const {
    const Vec3 p = fat_->cell_positions_m()[static_cast<std::size_t>(cell)];
    const NearestTube tube = NearestTubeTo(p);
    const double clearance_m = kTipRadius_m + tube.radius_m + 0.0002;
    if (tube.distance_m >= clearance_m || tube.distance_m < 1e-9) return p;
    const double offset_m = std::min(clearance_m - tube.distance_m, 0.8 * kBurnRadius_m);
    return p + offset_m * (p - tube.p_W_m) / tube.distance_m;
  }

  // Cells worth burning: intact ones in the triangle's slab, or hiding the cystic duct or artery.
  std::vector<int> FatTargets() const {
    const auto& cells = fat_->cells();
    const auto& description = fat_->description();
    std::vector<Vec3> samples;
    std::vector<double> reach;
    for (const int tube : {kCysticDuct, kCysticArtery}) {
      const double length_m = tubes_->TubeLength_m(tube);
      const double r = tubes_->description().tubes[static_cast<std::size_t>(tube)].material.outer_radius_m +
                       description.cover_margin_m;
      const int n = std::max(2, static_cast<int>(length_m / description.tube_sample_spacing_m) + 1);
      for (int k = 0; k < n; ++k) {
        samples.push_back(tubes_->PositionAt(tube, length_m * k / (n - 1)));
        reach.push_back(r);
      }
    }
    std::vector<int> targets;
    for (std::size_t c = 0; c < cells.size(); ++c) {
      if (cells[c].state != FatCellState::kIntact) continue;
      bool wanted = cells[c].in_triangle;
      for (std::size_t k = 0; k < samples.size() && !wanted; ++k)
        wanted = (fat_->cell_positions_m()[c] - samples[k]).norm() <= reach[k];
      if (wanted) targets.push_back(static_cast<int>(c));
    }
    return targets;
  }

  // Cell by cell, nearest first: to the burn point with the pedal up (a hop of 3 mm or less keeps
  // it down: the next cell is already within reach), pedal down until the cell is gone.
  void BurnFat() {
    const double t = session_.time_s();
    const auto intact = [&](int c) {
      return fat_->cells()[static_cast<std::size_t>(c)].state == FatCellState::kIntact;
    };
    if (burn_.stage == BurnStage::kBurn && !intact(burn_.target)) burn_.stage = BurnStage::kChoose;
    switch (burn_.stage) {
      case BurnStage::kChoose: {
        const bool was_burning = burn_.target >= 0 && pedal_was_down_;
        sight_.Update();
        std::vector<int> targets = FatTargets();
        // The hook's tip pushes a tube out of itself (tip radius plus the tube's), so a cell
        // nearer a tube's centreline than that less the burn radius never comes within reach.
        std::erase_if(targets, [&](int c) {
          const NearestTube tube = NearestTubeTo(fat_->cell_positions_m()[static_cast<std::size_t>(c)]);
          return tube.distance_m < kTipRadius_m + tube.radius_m - 0.8 * kBurnRadius_m;
        });
        std::sort(targets.begin(), targets.end(), [&](int a, int b) {
          return (fat_->cell_positions_m()[static_cast<std::size_t>(a)] - right_tip_).squaredNorm() <
                 (fat_->cell_positions_m()[static_cast<std::size_t>(b)] - right_tip_).squaredNorm();
        });
        burn_.target = -1;
        for (const int c : targets) {
          if (give_up_until_s_[static_cast<std::size_t>(c)] > t) continue;
          const Vec3 p = BurnPointFor(c);
          if (!sight_.Clear(right_.p_RemoteCentre_W, p)) continue;
          if (st_.scope_eye_W && !sight_.Clear(*st_.scope_eye_W, p)) continue;
          burn_.target = c;
          burn_.to = p;
          break;
        }
        if (burn_.target < 0) {
          // Nothing left the hook can take: the grasper spreads what hugs the tubes.
          if (targets.empty()) Enter(RightPhase::kSpread);
          break;
        }
        burn_.since = -1;
        burn_.started = t;
        const bool hop = was_burning && (burn_.to - right_tip_).norm() <= 0.003;
        burn_.stage = hop ? BurnStage::kBurn : BurnStage::kToStart;
        if (hop) {
          pedal_ = true;
          right_tip_ = MoveToward(right_tip_, burn_.to, max_step_);
        }
        break;
      }
      case BurnStage::kToStart:
        right_tip_ = MoveToward(right_tip_, burn_.to, max_step_);
        if ((right_tip_ - burn_.to).norm() < 1e-9) {
          if (burn_.since < 0) burn_.since = t;
          if (t - burn_.since >= kDwell_s) burn_.stage = BurnStage::kBurn, burn_.started = t;
        }
        break;
      case BurnStage::kBurn:
        if (t - burn_.started > st_.cell_burn_timeout_s) {
          give_up_until_s_[static_cast<std::size_t>(burn_.target)] = t + 10.0;
          burn_.stage = BurnStage::kChoose;
          break;
        }
        pedal_ = true;
        right_tip_ = MoveToward(right_tip_, BurnPointFor(burn_.target), max_step_);
        if (debug_ && scene_.steps() % 20 == 0) {
          const auto& cell = fat_->cells()[static_cast<std::size_t>(burn_.target)];
          std::fprintf(stderr, "  cell %d dose %.2f J tip-cell %.4f m commanded-tip %.4f m in_triangle %d anchor %d\n",
                       burn_.target, cell.dose_J,
                       (scene_.tool_tip(1) - fat_->cell_positions_m()[static_cast<std::size_t>(burn_.target)]).norm(),
                       (scene_.tool_tip(1) - right_tip_).norm(), cell.in_triangle ? 1 : 0, cell.anchor_tube);
        }
        break;
      case BurnStage::kBack:
        burn_.stage = BurnStage::kChoose;
        break;
    }
    pedal_was_down_ = pedal_;
  }

  // Blunt dissection with the grasper (its jaws' tips push the fat; a cell pushed beyond the
  // tear strain tears loose): the nearest fat worth removing that the grasper reaches from its
  // port and the scope sees, the tip brought to it with the jaws just open (open jaws straddle a
  // tube rather than push it), then spread and closed again: at three rolls 60 degrees apart
  // beside a tube, once in the open layer.
  void Spread() {
    const double t = session_.time_s();
    switch (spread_.stage) {
      case SpreadStage::kChoose: {
        sight_.Update();
        std::vector<int> targets = FatTargets();
        std::sort(targets.begin(), targets.end(), [&](int a, int b) {
          return (fat_->cell_positions_m()[static_cast<std::size_t>(a)] - grasp_tip_).squaredNorm() <
                 (fat_->cell_positions_m()[static_cast<std::size_t>(b)] - grasp_tip_).squaredNorm();
        });
        spread_.target = -1;
        bool waiting = false;
        for (const int c : targets) {
          if (give_up_until_s_[static_cast<std::size_t>(c)] > t) {
            waiting = true;
            continue;
          }
          const Vec3 p = fat_->cell_positions_m()[static_cast<std::size_t>(c)];
          if (!sight_.ClearOfLiver(grasper_.p_RemoteCentre_W, p)) continue;
          if (st_.scope_eye_W && !sight_.Clear(*st_.scope_eye_W, p)) continue;
          spread_.target = c;
          spread_.at = p;
          break;
        }
        if (spread_.target < 0) {
          if (debug_) {
            int port_blocked = 0, unseen = 0;
            for (const int c : targets) {
              const Vec3 p = fat_->cell_positions_m()[static_cast<std::size_t>(c)];
              port_blocked += !sight_.ClearOfLiver(grasper_.p_RemoteCentre_W, p);
              unseen += st_.scope_eye_W && !sight_.Clear(*st_.scope_eye_W, p);
            }
            std::fprintf(stderr,
                         "  spread: %zu targets, %d blocked from the port, %d unseen; duct seen %.2f uncovered %.2f\n",
                         targets.size(), port_blocked, unseen, session_.calot_step()->seen_fraction(kCysticDuct),
                         fat_->UncoveredFraction(kCysticDuct));
          }
          if (!waiting) spread_exhausted_ = true;
          break;
        }
        spread_.stage = SpreadStage::kToCell;
        spread_.roll = 0;
        {
          // Around a tube the jaws spread at three rolls; in the open layer one does.
          const NearestTube tube = NearestTubeTo(spread_.at);
          spread_.rolls = tube.distance_m < tube.radius_m + fat_->description().sleeve_thickness_m + 0.001 ? 3 : 1;
        }
        break;
      }
      case SpreadStage::kToCell:
        left_jaw_ = kSpreadClosed_rad;
        grasp_tip_ = MoveToward(grasp_tip_, spread_.at, max_step_);
        if ((grasp_tip_ - spread_.at).norm() < 1e-9) spread_.stage = SpreadStage::kSpread, spread_.since = t;
        break;
      case SpreadStage::kSpread: {
        // Open over 0.1 s, close over 0.1 s, at each of three rolls.
        const double u = (t - spread_.since) / 0.1;
        left_jaw_ = u < 1 ? kSpreadClosed_rad + u * (kJawOpen_rad - kSpreadClosed_rad)
                          : std::max(kSpreadClosed_rad, kJawOpen_rad - (u - 1) * (kJawOpen_rad - kSpreadClosed_rad));
        if (u >= 2) {
          spread_.since = t;
          if (++spread_.roll >= spread_.rolls) {
            const bool removed = fat_->cells()[static_cast<std::size_t>(spread_.target)].state != FatCellState::kIntact;
            if (!removed) give_up_until_s_[static_cast<std::size_t>(spread_.target)] = t + 10.0;
            spread_.stage = SpreadStage::kChoose;
            spread_.roll = 0;
          }
        }
        break;
      }
    }
    left_roll_ = spread_.roll * kPi / 3.0;
  }

  // Two clips on the patient's side of the planned cut and one on the gallbladder's, for the
  // cystic duct and the artery, then the scissors between them; or the failure's few actions.
  void PlanJawActions() {
    switch (script_) {
      case CalotScript::kCorrectDissection:
      case CalotScript::kClipBeforeCriticalView:
        for (const int tube : {kCysticDuct, kCysticArtery}) {
          const double cut_s = PlannedCut(tube);
          const double length_m = tubes_->TubeLength_m(tube);
          const double step_s = std::min(st_.clip_spacing_m, 0.22 * length_m) / length_m;
          for (const double s : {cut_s - 2 * step_s, cut_s - step_s, cut_s + step_s})
            actions_.push_back({InstrumentTool::kClipApplier, tube, s});
        }
        for (const int tube : {kCysticDuct, kCysticArtery})
          actions_.push_back({InstrumentTool::kScissors, tube, PlannedCut(tube)});
        break;
      case CalotScript::kArteryCutWithoutClips:
        actions_.push_back({InstrumentTool::kScissors, kCysticArtery, PlannedCut(kCysticArtery)});
        break;
      case CalotScript::kClipCommonBileDuct:
        actions_.push_back({InstrumentTool::kClipApplier, kCommonBileDuct, 0.5});
        break;
    }
  }

  // The scenario's planned cut, as the session's snapshot carries it (after the first step).
  double PlannedCut(int tube) const {
    return session_.calot_step()->last_snapshot().structures.at(static_cast<std::size_t>(tube)).planned_cut_s;
  }

  // One jaw action: open jaws to the tube's point (live), still, close, still, check, open, still.
  enum class JawStage { kApproach, kClose, kCheck, kOpen };
  void JawStep() {
    const double t = session_.time_s();
    if (next_action_ >= actions_.size()) {  // the last one done: jaws open, still
      if (t - stage_start_ >= kDwell_s) Enter(RightPhase::kHome);
      return;
    }
    const JawAction& a = actions_[next_action_];
    const Vec3 target = tubes_->PositionAt(a.tube, a.s * tubes_->TubeLength_m(a.tube));
    switch (jaw_step_) {
      case JawStage::kApproach:
        if (!jaw_adjusted_) KeepClear(actions_[next_action_]);
        right_jaw_ = kJawOpen_rad;
        right_tip_ = MoveToward(right_tip_, target, max_step_);
        if ((right_tip_ - target).norm() < 1e-9) {
          jaw_step_ = JawStage::kClose;
          stage_start_ = t;
          done_before_ = ActionsOn(a);
        }
        break;
      case JawStage::kClose:
        right_tip_ = target;  // within a step's reach: the tube barely moves
        if (t - stage_start_ >= kDwell_s && !JawsHoldTheTarget(actions_[next_action_])) {
          // Another tube lies nearer the jaws (the common duct beside a short cystic duct's
          // junction): a surgeon would not fire; 0.4 mm nearer the planned cut and look again.
          JawAction& moved = actions_[next_action_];
          const double step_s = 0.0004 / tubes_->TubeLength_m(moved.tube);
          moved.s += moved.s < PlannedCut(moved.tube) ? step_s : -step_s;
          if (++jaw_tries_ >= 12) {
            jaw_tries_ = 0;
            ++next_action_;
          }
          jaw_step_ = JawStage::kApproach;
          break;
        }
        if (t - stage_start_ >= kDwell_s) {
          right_jaw_ = 0;
          jaw_step_ = JawStage::kCheck;
          stage_start_ = t;
        }
        break;
      case JawStage::kCheck:
        if (t - stage_start_ >= kDwell_s) {
          right_jaw_ = kJawOpen_rad;
          jaw_step_ = JawStage::kOpen;
          stage_start_ = t;
          if (debug_ && ActionsOn(a) == done_before_) {
            const auto jaws = session_.calot_step()->RightJawSegment(scene_, PoseFor(right_, right_tip_, 0.0));
            const auto hit = tubes_->NearestToSegment(jaws[0], jaws[1], 0.004);
            std::fprintf(stderr, "  %s on tube %d at s %.3f did nothing; the jaws' nearest: tube %d s %.3f gap %.4f\n",
                         a.tool == InstrumentTool::kClipApplier ? "clip" : "cut", a.tube, a.s, hit ? hit->tube : -1,
                         hit ? hit->s_m / tubes_->TubeLength_m(hit->tube) : -1.0, hit ? hit->surface_gap_m : 0.0);
          }
          if (ActionsOn(a) > done_before_ || ++jaw_tries_ >= 3) {
            jaw_tries_ = 0;
            ++next_action_;
            jaw_adjusted_ = false;
          }
        }
        break;
      case JawStage::kOpen:
        if (t - stage_start_ >= kDwell_s) {
          if (actions_[next_action_].tool != right_tool_)
            Enter(RightPhase::kExchange);
          else
            jaw_step_ = JawStage::kApproach;
        }
        break;
    }
  }

  // What the closing jaws would take now: the tube nearest their segment, within a millimetre
  // of the planned point along it.
  bool JawsHoldTheTarget(const JawAction& a) const {
    const auto jaws = session_.calot_step()->RightJawSegment(scene_, PoseFor(right_, right_tip_, 0.0));
    const auto hit = tubes_->NearestToSegment(jaws[0], jaws[1], 0.004);
    return hit && hit->tube == a.tube && std::abs(hit->s_m - a.s * tubes_->TubeLength_m(a.tube)) < 0.001;
  }

  // A clip on the patient's side goes at least 1.4 mm beyond the one before it on that tube (the
  // clips are 1.2 mm wide), and no nearer the planned cut than 0.8 mm.
  void KeepClear(JawAction& a) {
    jaw_adjusted_ = true;
    if (a.tool != InstrumentTool::kClipApplier) return;
    const double length_m = tubes_->TubeLength_m(a.tube), cut_s = PlannedCut(a.tube);
    if (a.s >= cut_s) return;
    for (const auto& clip : tubes_->clips())
      if (clip.tube == a.tube && clip.s_m / length_m < cut_s)
        a.s = std::max(a.s, clip.s_m / length_m + 0.0014 / length_m);
    a.s = std::min(a.s, cut_s - 0.0008 / length_m);
  }

  std::size_t ActionsOn(const JawAction& a) const {
    std::size_t n = 0;
    if (a.tool == InstrumentTool::kClipApplier) {
      for (const auto& clip : tubes_->clips()) n += clip.tube == a.tube;
    } else {
      for (const auto& cut : tubes_->cuts()) n += cut.tube == a.tube;
    }
    return n;
  }

  void Record() {
    device::InputFrame f;
    f.time_s = session_.time_s();
    f.right_tool = right_tool_;
    f.instruments[0].pose = PoseFor(grasper_, grasp_tip_, left_jaw_);
    f.instruments[0].pose.roll_rad = left_roll_;
    f.instruments[1].pose = PoseFor(right_, right_tip_, right_tool_ == InstrumentTool::kCauteryHook ? 0.0 : right_jaw_);
    f.instruments[1].pedal = pedal_ && right_tool_ == InstrumentTool::kCauteryHook;
    const SessionStepReport r = session_.Step(f);
    frames_.push_back(f);
    if (st_.on_step) st_.on_step(session_, r);
  }

  void Log() const {
    const calot::CalotSnapshot& s = session_.calot_step()->last_snapshot();
    const calot::CvsAssessment& a = session_.calot_metrics()->LatestAssessment();
    std::fprintf(stderr,
                 "t %6.2f s phase %d grasp %d fat cleared %.3f lower third %.2f seen duct %.2f artery %.2f "
                 "(cvs %d%d%d) clips %zu cuts %zu springs alive %d\n",
                 session_.time_s(), static_cast<int>(phase_), holding_ ? 1 : 0, s.fat_removed_fraction,
                 s.lower_third_separated_fraction, s.structures[kCysticDuct].visible_fraction,
                 s.structures[kCysticArtery].visible_fraction, a.triangle_cleared ? 1 : 0,
                 a.lower_third_separated ? 1 : 0, a.two_structures_seen ? 1 : 0, tubes_->clips().size(),
                 tubes_->cuts().size(), scene_.tissue().num_alive());
  }

  static constexpr double kTipRadius_m = 0.0025;  // CalotToolGeometry::tip_radius_m
  static constexpr double kBurnRadius_m = 0.002;  // CalotToolGeometry::hook_burn_radius_m

  DissectionSession& session_;
  const physics::DissectionScene& scene_;
  const physics::DissectionModel& model_;
  CalotScript script_;
  CalotSurgeonSettings st_;
  double h_, max_step_;
  const physics::InstrumentMount& grasper_;
  const physics::InstrumentMount& right_;
  OrganSight sight_;
  const physics::calot::TriangleStructures* tubes_ = nullptr;
  const physics::calot::FatLayer* fat_ = nullptr;
  std::vector<device::InputFrame> frames_;
  bool done_ = false;
  bool debug_ = std::getenv("VESICA_SCRIPT_DEBUG") != nullptr;

  // Left hand.
  int pouch_vertex_ = -1;
  Vec3 grasp_tip_ = Vec3::Zero(), retract_origin_ = Vec3::Zero();
  double left_jaw_ = kJawOpen_rad, arrived_at_ = -1, grasp_offset_m_ = 0.001, pull_m_ = 0, held_since_ = 0;
  bool holding_ = false;
  LeftMode left_mode_ = LeftMode::kHoldPouch;
  Vec3 grasp_home_ = Vec3::Zero();
  double left_roll_ = 0;
  enum class SpreadStage { kChoose, kToCell, kSpread };
  struct SpreadMove {
    SpreadStage stage = SpreadStage::kChoose;
    int target = -1, roll = 0, rolls = 3;
    Vec3 at = Vec3::Zero();
    double since = 0;
  } spread_;
  bool spread_exhausted_ = false;

  // Right hand.
  RightPhase phase_ = RightPhase::kWait;
  double phase_start_ = 0;
  Vec3 right_home_ = Vec3::Zero(), right_tip_ = Vec3::Zero();
  InstrumentTool right_tool_ = InstrumentTool::kCauteryHook;
  double right_jaw_ = 0;
  bool pedal_ = false, pedal_was_down_ = false;
  enum class BurnStage { kChoose, kToStart, kBurn, kBack };
  struct BurnMove {
    BurnStage stage = BurnStage::kChoose;
    int target = -1, tries = 0;
    Vec3 from = Vec3::Zero(), to = Vec3::Zero();
    double since = -1, started = 0;
  } burn_;
  std::vector<double> give_up_until_s_, membrane_give_up_until_s_;
  std::vector<JawAction> actions_;
  std::size_t next_action_ = 0, done_before_ = 0;
  JawStage jaw_step_ = JawStage::kApproach;
  double stage_start_ = 0;
  int jaw_tries_ = 0;
  bool jaw_adjusted_ = false;
};

}  // namespace

std::string CalotScriptName(CalotScript script) {
  switch (script) {
    case CalotScript::kCorrectDissection:
      return "correct";
    case CalotScript::kClipBeforeCriticalView:
      return "clip-before-view";
    case CalotScript::kArteryCutWithoutClips:
      return "artery-cut-unclipped";
    case CalotScript::kClipCommonBileDuct:
      return "clip-common-bile-duct";
  }
  return "unknown";
}

std::vector<device::InputFrame> RunScriptedCalot(DissectionSession& session, CalotScript script,
                                                 const CalotSurgeonSettings& settings) {
  return CalotSurgeon(session, script, settings).Run();
}

}  // namespace vesica::app
