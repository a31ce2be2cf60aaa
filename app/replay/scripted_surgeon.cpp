#include "app/replay/scripted_surgeon.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include "physics/tissue/connective_tissue.h"

namespace vesica::app {

namespace {
using Vec3 = Eigen::Vector3d;

Vec3 MoveToward(const Vec3& from, const Vec3& to, double max_step) {
  const Vec3 d = to - from;
  const double n = d.norm();
  return n <= max_step ? to : Vec3(from + d * (max_step / n));
}

physics::InstrumentPose PoseFor(const physics::InstrumentMount& m, const Vec3& tip, double jaw) {
  physics::InstrumentPose p =
      physics::AimAt(m.p_RemoteCentre_W, tip, (tip - m.p_RemoteCentre_W).norm(), m.reference_direction_W);
  p.jaw_angle_rad = jaw;
  return p;
}

// Outward vertex normals of the gallbladder's boundary at the current positions.
physics::Vertices VertexNormals(const physics::TriangleMesh& surface, const physics::Vertices& x) {
  physics::Vertices n = physics::Vertices::Zero(x.rows(), 3);
  for (int f = 0; f < surface.num_triangles(); ++f) {
    const Vec3 a = x.row(surface.triangles(f, 0)), b = x.row(surface.triangles(f, 1)),
               c = x.row(surface.triangles(f, 2));
    const Vec3 fn = (b - a).cross(c - a);
    for (int k = 0; k < 3; ++k) n.row(surface.triangles(f, k)) += fn.transpose();
  }
  n.rowwise().normalize();
  return n;
}
}  // namespace

std::vector<device::InputFrame> RunScriptedDissection(DissectionSession& session, const ScriptedSurgeonSettings& st) {
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
  double arrived_at = -1;
  double jaw = 0.5, approach_offset = 0.001, phase_start = 0, spring_start = 0;
  int target_spring = -1;
  std::vector<device::InputFrame> frames;
  const int total = static_cast<int>(model.tissue.springs.size());

  while (phase != Phase::kDone && session.time_s() < st.max_session_s) {
    const double t = session.time_s();
    bool pedal = false;
    const physics::Vertices x = scene.gallbladder_surface_positions();
    switch (phase) {
      case Phase::kApproach: {
        // Move to just outside the fundus, keep still for kDwell, close, keep still for kDwell,
        // then check the hold: every event sits between stills, so a replay that interpolates
        // the recording's frames reproduces it.
        constexpr double kDwell = 0.1;
        if (arrived_at < 0) {
          const physics::Vertices n = VertexNormals(surface, x);
          const Vec3 target = x.row(fundus).transpose() + approach_offset * n.row(fundus).transpose();
          grasp_tip = MoveToward(grasp_tip, target, max_step);
          if ((grasp_tip - target).norm() < 1e-9) arrived_at = t;
        } else if (jaw > 0.0 && t - arrived_at >= kDwell) {
          jaw = 0.0;
        } else if (jaw == 0.0 && t - arrived_at >= 2 * kDwell) {
          if (scene.grasp().state() == physics::GraspStateMachine::State::kHolding) {
            phase = Phase::kRetract;
            retract_origin = grasp_tip;
            phase_start = t;
          } else {
            jaw = 0.5;
            approach_offset -= 0.0005;  // a little deeper next time
          }
          arrived_at = -1;
        }
        break;
      }
      case Phase::kRetract:
      case Phase::kDissect: {
        if (scene.grasp().state() != physics::GraspStateMachine::State::kHolding) {  // slipped: take it again
          phase = Phase::kApproach;
          jaw = 0.5;
          approach_offset = 0.001;
          arrived_at = -1;
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
    device::InputFrame f;
    f.time_s = t;
    f.instruments[0].pose = PoseFor(grasper, grasp_tip, jaw);
    f.instruments[1].pose = PoseFor(hook, hook_tip, 0.0);
    f.instruments[1].pedal = pedal;
    const SessionStepReport r = session.Step(f);
    frames.push_back(f);
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

}  // namespace vesica::app
