// The emulator's geometry is the "world"; the host's kinematics model must agree with it.
#include "firmware_protocol/emulator/arm_geometry.h"

#include <gtest/gtest.h>

#include "device/spherical_arm_kinematics.h"

namespace vesica::fp::emulator {
namespace {

TEST(ArmGeometryTest, HostKinematicsAgreeWithPlantGeometry) {
  const Vec3 f{0.4, -1.1, 0.9};
  for (const Joint4& q : {Joint4{0, 0, 0, 0.1}, Joint4{0.6, -0.4, 1.0, 0.07}, Joint4{-1.0, 0.9, -2.0, 0.24}}) {
    const auto host_q = device::ArmJoints{q[0], q[1], q[2], q[3]};
    const Vec3 p = TipPosition(q);
    const Eigen::Vector3d p_host = device::ForwardKinematics(host_q).p_TTip_T;
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(p[k], p_host[k], 1e-15);
    const Joint4 tau = JointEffortsOfTipForce(q, f);
    const Eigen::Vector4d tau_host = device::JointEffortsFromTipForce(host_q, Eigen::Vector3d(f[0], f[1], f[2]));
    for (int j = 0; j < 4; ++j) EXPECT_NEAR(tau[j], tau_host[j], 1e-14);
    const Vec3 back = TipForceOfJointEfforts(q, tau);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(back[k], f[k], 1e-12);
  }
}

TEST(ArmGeometryTest, TipVelocityIsDerivativeOfPosition) {
  const Joint4 q{0.3, -0.5, 0.2, 0.15};
  const Joint4 qd{0.7, -0.4, 5.0, 0.03};
  const double h = 1e-7;
  Joint4 q1 = q;
  for (int j = 0; j < 4; ++j) q1[j] += h * qd[j];
  const Vec3 p0 = TipPosition(q), p1 = TipPosition(q1), v = TipVelocity(q, qd);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR((p1[k] - p0[k]) / h, v[k], 1e-6);
}

}  // namespace
}  // namespace vesica::fp::emulator
