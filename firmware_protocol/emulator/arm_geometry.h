#pragma once

#include <array>

namespace vesica::fp::emulator {

/// The real arm's geometry as the plant sees it: a spherical remote-centre mechanism, trocar
/// frame T at the pivot with +z the nominal shaft direction. Joint order: yaw, pitch, roll,
/// insertion. Kept apart from device/ on purpose: the host's kinematic model is checked against
/// this "world", not derived from it.
using Vec3 = std::array<double, 3>;
using Joint4 = std::array<double, 4>;

/// Unit shaft axis Ry(yaw) Rx(pitch) e_z in T.
Vec3 ShaftAxis(double yaw_rad, double pitch_rad);
/// Tip position in T, m.
Vec3 TipPosition(const Joint4& q);
/// Tip linear velocity in T for joint rates qd, m/s.
Vec3 TipVelocity(const Joint4& q, const Joint4& qd);
/// Joint efforts of a tip force, Jv^T f (N m for yaw, pitch; 0 for roll; N for insertion).
Joint4 JointEffortsOfTipForce(const Joint4& q, const Vec3& f_T);
/// Tip force produced by joint efforts of yaw, pitch and insertion (inverse of the above;
/// needs insertion > 0).
Vec3 TipForceOfJointEfforts(const Joint4& q, const Joint4& tau);

}  // namespace vesica::fp::emulator
