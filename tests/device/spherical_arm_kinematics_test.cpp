#include "device/spherical_arm_kinematics.h"

#include <cmath>

#include <gtest/gtest.h>

namespace vesica::device {
namespace {

// Poses spread over the arm's workspace (yaw, pitch within +-60 deg, roll any, depth 2..25 cm).
std::vector<ArmJoints> SamplePoses() {
  return {{0.0, 0.0, 0.0, 0.12},   {0.3, -0.2, 1.0, 0.05},  {-0.9, 0.7, -2.5, 0.2},
          {1.0, 1.0, 3.0, 0.25},   {-0.5, -1.0, 0.4, 0.02}, {0.05, 0.9, -0.1, 0.15}};
}

// Angular velocity from a finite rotation: log(R1 R0^T) / h, small-angle vee of the skew part.
Eigen::Vector3d AngularRate(const Eigen::Matrix3d& R0, const Eigen::Matrix3d& R1, double h) {
  const Eigen::AngleAxisd aa(R1 * R0.transpose());
  return aa.axis() * aa.angle() / h;
}

TEST(SphericalArmKinematicsTest, ZeroPoseTipLiesOnTrocarAxis) {
  const TipPose pose = ForwardKinematics({0.0, 0.0, 0.0, 0.1});
  EXPECT_TRUE(pose.p_TTip_T.isApprox(Eigen::Vector3d(0, 0, 0.1)));
  EXPECT_TRUE(pose.R_TTip.isIdentity(1e-15));
}

TEST(SphericalArmKinematicsTest, YawSwingsTipTowardPlusX) {
  // 90 degrees of yaw about +y turns +z into +x; tip distance from the pivot is the insertion.
  const TipPose pose = ForwardKinematics({M_PI / 2, 0.0, 0.0, 0.2});
  EXPECT_NEAR(pose.p_TTip_T.x(), 0.2, 1e-12);
  EXPECT_NEAR(pose.p_TTip_T.z(), 0.0, 1e-12);
  // Positive pitch about x tips the shaft toward -y.
  EXPECT_LT(ForwardKinematics({0.0, 0.3, 0.0, 0.1}).p_TTip_T.y(), 0.0);
}

TEST(SphericalArmKinematicsTest, JacobianMatchesCentralDifferences) {
  const double h = 1e-6;
  for (const ArmJoints& q : SamplePoses()) {
    const Eigen::Matrix<double, 6, 4> J = TipJacobian(q);
    for (int j = 0; j < 4; ++j) {
      Eigen::Vector4d qp = q.AsVector(), qm = q.AsVector();
      qp[j] += h;
      qm[j] -= h;
      const TipPose Pp = ForwardKinematics(ArmJoints::FromVector(qp));
      const TipPose Pm = ForwardKinematics(ArmJoints::FromVector(qm));
      const Eigen::Vector3d v_fd = (Pp.p_TTip_T - Pm.p_TTip_T) / (2 * h);
      const Eigen::Vector3d w_fd = AngularRate(Pm.R_TTip, Pp.R_TTip, 2 * h);
      EXPECT_LT((J.block<3, 1>(0, j) - v_fd).norm(), 1e-8) << "joint " << j;
      EXPECT_LT((J.block<3, 1>(3, j) - w_fd).norm(), 1e-7) << "joint " << j;
    }
  }
}

TEST(SphericalArmKinematicsTest, PoseJointsRoundTrip) {
  for (const ArmJoints& q : SamplePoses()) {
    ArmJoints back;
    ASSERT_TRUE(InverseKinematics(ForwardKinematics(q), &back));
    EXPECT_NEAR(back.yaw_rad, q.yaw_rad, 1e-12);
    EXPECT_NEAR(back.pitch_rad, q.pitch_rad, 1e-12);
    EXPECT_NEAR(back.roll_rad, q.roll_rad, 1e-12);
    EXPECT_NEAR(back.insertion_m, q.insertion_m, 1e-15);
  }
}

TEST(SphericalArmKinematicsTest, InverseRejectsPivotAndOutwardShaft) {
  ArmJoints q{0.1, 0.2, 0.3, 0.4};
  TipPose at_pivot;
  EXPECT_FALSE(InverseKinematics(at_pivot, &q));
  TipPose outward;
  outward.p_TTip_T = {0.0, 0.0, -0.1};
  EXPECT_FALSE(InverseKinematics(outward, &q));
  TipPose nan_pose;
  nan_pose.p_TTip_T = {NAN, 0.0, 0.1};
  EXPECT_FALSE(InverseKinematics(nan_pose, &q));
  EXPECT_EQ(q.insertion_m, 0.4);  // untouched on failure
}

TEST(SphericalArmKinematicsTest, JacobianTransposeIsPowerConsistent) {
  // Virtual work: f . (Jv qd) == (Jv^T f) . qd for any force and joint rate.
  const Eigen::Vector3d f(0.7, -1.3, 2.1);
  const Eigen::Vector4d qd(0.4, -0.2, 3.0, 0.05);
  for (const ArmJoints& q : SamplePoses()) {
    const Eigen::Vector3d v = TipJacobian(q).topRows<3>() * qd;
    EXPECT_NEAR(f.dot(v), JointEffortsFromTipForce(q, f).dot(qd), 1e-12);
    EXPECT_EQ(JointEffortsFromTipForce(q, f)[2], 0.0);  // no roll moment from a tip force
  }
}

TEST(SphericalArmKinematicsTest, TipForceFromEffortsInvertsJacobianTranspose) {
  const Eigen::Vector3d f(0.7, -1.3, 2.1);
  for (const ArmJoints& q : SamplePoses()) {
    const Eigen::Vector3d back = TipForceFromJointEfforts(q, JointEffortsFromTipForce(q, f));
    EXPECT_LT((back - f).norm(), 1e-12);
  }
}

}  // namespace
}  // namespace vesica::device
