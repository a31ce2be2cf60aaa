#include "firmware_protocol/emulator/arm_geometry.h"

#include <cmath>

namespace vesica::fp::emulator {
namespace {

// The three actuated columns of Jv; they are mutually orthogonal.
void Columns(const Joint4& q, Vec3* c_yaw, Vec3* c_pitch, Vec3* c_ins) {
  const double cy = std::cos(q[0]), sy = std::sin(q[0]);
  const double cp = std::cos(q[1]), sp = std::sin(q[1]);
  const double d = q[3];
  *c_yaw = {d * cp * cy, 0.0, -d * cp * sy};
  *c_pitch = {-d * sp * sy, -d * cp, -d * sp * cy};
  *c_ins = {cp * sy, -sp, cp * cy};
}

double Dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

}  // namespace

Vec3 ShaftAxis(double yaw_rad, double pitch_rad) {
  const double cp = std::cos(pitch_rad);
  return {cp * std::sin(yaw_rad), -std::sin(pitch_rad), cp * std::cos(yaw_rad)};
}

Vec3 TipPosition(const Joint4& q) {
  const Vec3 a = ShaftAxis(q[0], q[1]);
  return {q[3] * a[0], q[3] * a[1], q[3] * a[2]};
}

Vec3 TipVelocity(const Joint4& q, const Joint4& qd) {
  Vec3 cy, cp, ci;
  Columns(q, &cy, &cp, &ci);
  Vec3 v{};
  for (int k = 0; k < 3; ++k) v[k] = cy[k] * qd[0] + cp[k] * qd[1] + ci[k] * qd[3];
  return v;
}

Joint4 JointEffortsOfTipForce(const Joint4& q, const Vec3& f_T) {
  Vec3 cy, cp, ci;
  Columns(q, &cy, &cp, &ci);
  return {Dot(cy, f_T), Dot(cp, f_T), 0.0, Dot(ci, f_T)};
}

Vec3 TipForceOfJointEfforts(const Joint4& q, const Joint4& tau) {
  Vec3 c[3];
  Columns(q, &c[0], &c[1], &c[2]);
  const double t[3] = {tau[0], tau[1], tau[3]};
  Vec3 f{};
  for (int j = 0; j < 3; ++j) {
    const double n2 = Dot(c[j], c[j]);
    if (n2 < 1e-12) continue;
    for (int k = 0; k < 3; ++k) f[k] += c[j][k] * t[j] / n2;
  }
  return f;
}

}  // namespace vesica::fp::emulator
