// Friction: constant-velocity sweeps across the middle of the range, both directions, several
// speeds; all joints at once. Over a window at constant speed the mean commanded torque is the
// friction (plus, for pitch, the window's mean gravity: the same both ways).
#include <algorithm>
#include <cmath>

#include "device/calibration/calibration_abort.h"
#include "device/calibration/calibration_step.h"
#include "device/calibration/friction_fit.h"

namespace vesica::device::calibration {
namespace {

// Each commanded torque counts for as long as it stood (until the next command): on a host that
// stalls, the cycles come unevenly, and a plain mean would weigh a catch-up burst of commands as
// much as the command that stood through the stall. A command the node cut (its joint state
// names a limiter: the session's speed or current bound) did not stand as sent and is left out.
struct Window {
  double lo = 0.0, hi = 0.0;  // position window
  double torque_time = 0.0;   // integral of the commanded torque over the time it stood
  double time = 0.0;          // how long the counted commands stood
  int n = 0;
  double t0 = 0.0, p0 = 0.0, t1 = 0.0, p1 = 0.0, last_torque = 0.0;
  bool last_limited = false;
  void Add(double t, double p, double torque, bool limited) {
    if (n == 0) {
      t0 = t;
      p0 = p;
    } else if (!last_limited) {
      torque_time += last_torque * (t - t1);
      time += t - t1;
    }
    t1 = t;
    p1 = p;
    last_torque = torque;
    last_limited = limited;
    ++n;
  }
  double mean_torque() const { return time > 0.0 ? torque_time / time : 0.0; }
};

}  // namespace

void IdentifyFriction(StepContext& ctx) {
  ctx.Progress("friction", 0.0);
  JointServo& servo = ctx.servo;
  ctx.EngageSelected();
  const ArmDesign& d = servo.design();
  std::size_t segments = 0;
  for (int j = 0; j < 3; ++j)
    if (ctx.selected(j)) segments = std::max(segments, ctx.plan.friction_speeds[j].size());
  std::array<double, 3> a{}, b{};
  for (int j = 0; j < 3; ++j) {
    if (!ctx.selected(j)) continue;
    const JointCalibration& r = ctx.result.joint[j];
    a[j] = r.lower_stop + ctx.plan.sweep_margin[j];
    b[j] = r.upper_stop - ctx.plan.sweep_margin[j];
    servo.SetTorqueLimit(j, 0.9 * ctx.plan.session_max_current_A * d.nm_per_A[j]);
    servo.MoveTo(j, a[j], ctx.plan.move_speed[j]);
  }
  auto all_arrived = [&] {
    for (int j = 0; j < 3; ++j)
      if (ctx.selected(j) && !servo.arrived(j)) return false;
    return true;
  };
  ctx.RunUntil(all_arrived, 30.0, "friction: joints did not reach the sweep start");
  for (std::size_t k = 0; k < segments; ++k) {
    for (int direction : {+1, -1}) {
      // A sweep that did not hold its speed within 5 % (a host or an arm that stalled: its
      // commands came late) is swept again, from its start, up to twice; the checks judge the last.
      for (int attempt = 0;; ++attempt) {
        std::array<Window, 3> w;
        std::array<bool, 3> active{};
        for (int j = 0; j < 3; ++j) {
          if (!ctx.selected(j) || k >= ctx.plan.friction_speeds[j].size()) continue;
          active[j] = true;
          const double length = b[j] - a[j];
          // The middle half of the sweep: the start's transient has died out.
          w[j].lo = a[j] + 0.25 * length;
          w[j].hi = b[j] - 0.25 * length;
          servo.MoveTo(j, direction > 0 ? b[j] : a[j], ctx.plan.friction_speeds[j][k]);
        }
        ctx.RunUntil(
            [&] {
              bool done = true;
              for (int j = 0; j < 3; ++j) {
                if (!active[j]) continue;
                const double p = ctx.link.sample().position[j];
                if (!servo.arrived(j) && p >= w[j].lo && p <= w[j].hi)
                  w[j].Add(ctx.link.sample().t_s, p, servo.torque(j), ctx.link.sample().limiter != fp::Limiter::None);
                done = done && servo.arrived(j);
              }
              return done;
            },
            120.0, "friction: a sweep did not finish");
        ctx.RunFor(0.1);
        std::array<FrictionSegment, 3> found{};
        bool steady = true;
        for (int j = 0; j < 3; ++j) {
          if (!active[j]) continue;
          if (w[j].n < 20 || w[j].time < 0.5 * (w[j].t1 - w[j].t0))
            throw CalibrationAbort(AbortReason::kMeasurement,
                                   "friction: joint " + std::to_string(j) + " sweep too short to measure");
          found[j].velocity = (w[j].p1 - w[j].p0) / (w[j].t1 - w[j].t0);
          found[j].torque = w[j].mean_torque();
          const double speed = ctx.plan.friction_speeds[j][k];
          steady = steady && std::abs(found[j].velocity - direction * speed) <= 0.05 * speed;
        }
        if (steady || attempt == 2) {
          for (int j = 0; j < 3; ++j)
            if (active[j]) ctx.result.joint[j].friction_segments.push_back(found[j]);
          break;
        }
        for (int j = 0; j < 3; ++j)
          if (active[j]) servo.MoveTo(j, direction > 0 ? a[j] : b[j], ctx.plan.move_speed[j]);
        ctx.RunUntil(all_arrived, 30.0, "friction: joints did not return to a sweep's start");
      }
      ctx.Progress("friction",
                   static_cast<double>(2 * k + (direction > 0 ? 1 : 2)) / static_cast<double>(2 * segments));
    }
  }
  for (int j = 0; j < 3; ++j) {
    if (!ctx.selected(j)) continue;
    JointCalibration& r = ctx.result.joint[j];
    const FrictionFit fit = FitFriction(r.friction_segments);
    if (!fit.ok || fit.coulomb < 0 || fit.viscous < 0)
      throw CalibrationAbort(AbortReason::kMeasurement,
                             "friction: joint " + std::to_string(j) + " gave no physical fit");
    r.coulomb = fit.coulomb;
    r.viscous = fit.viscous;
    r.friction_offset = fit.offset;
    r.friction_rms = fit.rms;
    servo.MoveTo(j, d.centre[j], ctx.plan.move_speed[j]);
  }
  ctx.RunUntil(all_arrived, 30.0, "friction: joints did not return to the centre");
  ctx.Progress("friction", 1.0);
}

}  // namespace vesica::device::calibration
