#include "physics/scene/haptic_contact_frame.h"

#include <gtest/gtest.h>

#include <atomic>
#include <limits>
#include <stdexcept>
#include <thread>

#include "physics/scene/haptic_force_renderer.h"
#include "physics/scene/triple_buffer.h"

namespace vesica::physics {
namespace {

HapticContactFrame Contact(double lambda, double k) {
  HapticContactFrame f;
  f.active = true;
  f.unilateral = true;
  f.normal_W = Eigen::Vector3d::UnitY();
  f.p_Tool_W = Eigen::Vector3d(0, 0.01, 0);
  f.f_Tool_W = lambda * f.normal_W;
  f.stiffness_N_per_m = k * f.normal_W * f.normal_W.transpose();
  return f;
}

TEST(HapticContactFrameTest, ContactForceGrowsWithPenetrationAndLetsGo) {
  const HapticContactFrame f = Contact(0.5, 200.0);
  EXPECT_TRUE(RenderContactForce(f, f.p_Tool_W).isApprox(Eigen::Vector3d(0, 0.5, 0)));
  // 1 mm deeper (against the normal): 0.2 N more.
  EXPECT_NEAR(RenderContactForce(f, f.p_Tool_W - 1e-3 * f.normal_W).y(), 0.7, 1e-12);
  // Sliding along the surface does not change a frictionless contact.
  EXPECT_NEAR(RenderContactForce(f, f.p_Tool_W + Eigen::Vector3d(2e-3, 0, 0)).y(), 0.5, 1e-12);
  // Backed out by more than lambda / k = 2.5 mm: no force (never a pull).
  EXPECT_TRUE(RenderContactForce(f, f.p_Tool_W + 3e-3 * f.normal_W).isZero());
  HapticContactFrame idle;
  EXPECT_TRUE(RenderContactForce(idle, Eigen::Vector3d::Ones()).isZero());
}

TEST(HapticContactFrameTest, GraspPullsBack) {
  HapticContactFrame f;
  f.active = true;
  f.unilateral = false;
  f.stiffness_N_per_m = 300.0 * Eigen::Matrix3d::Identity();
  const Eigen::Vector3d pulled = f.p_Tool_W + Eigen::Vector3d(0, 0, 0.01);
  EXPECT_TRUE(RenderContactForce(f, pulled).isApprox(Eigen::Vector3d(0, 0, -3.0)));
}

TEST(TripleBufferTest, ReaderSeesLatestValue) {
  TripleBuffer<int> buffer(7);
  EXPECT_EQ(buffer.Latest(), 7);
  buffer.Publish(1);
  buffer.Publish(2);
  EXPECT_EQ(buffer.Latest(), 2);
  EXPECT_EQ(buffer.Latest(), 2);
  buffer.Publish(3);
  EXPECT_EQ(buffer.Latest(), 3);
}

// A writer publishes frames whose fields all carry the same counter; a concurrent reader must
// never see a mixed (torn) frame and must see counters that never go backwards.
TEST(TripleBufferTest, ConcurrentReaderNeverSeesTornOrOlderFrames) {
  TripleBuffer<HapticContactFrame> buffer;
  std::atomic<bool> done{false};
  constexpr int kFrames = 200000;
  std::thread writer([&] {
    for (int i = 1; i <= kFrames; ++i) {
      HapticContactFrame f;
      f.time_s = i;
      f.p_Tool_W.setConstant(i);
      f.f_Tool_W.setConstant(i);
      f.stiffness_N_per_m.setConstant(i);
      buffer.Publish(f);
    }
    done = true;
  });
  double last = 0;
  long reads = 0, torn = 0, backwards = 0;
  while (!done || last < kFrames) {
    const HapticContactFrame& f = buffer.Latest();
    const double t = f.time_s;
    if ((f.p_Tool_W.array() != t).any() || (f.f_Tool_W.array() != t).any() || (f.stiffness_N_per_m.array() != t).any())
      ++torn;
    if (t < last) ++backwards;
    last = t;
    ++reads;
  }
  writer.join();
  EXPECT_EQ(torn, 0);
  EXPECT_EQ(backwards, 0);
  EXPECT_EQ(last, kFrames);
  EXPECT_GT(reads, 0);
}

}  // namespace
}  // namespace vesica::physics

namespace vesica::physics {
namespace {

TEST(HapticForceRendererTest, NewFrameFadesInWithoutAJump) {
  HapticContactFrame a;
  a.active = true;
  a.unilateral = false;
  a.f_Tool_W = Eigen::Vector3d(0, 0, 1.0);
  a.stiffness_N_per_m = 100.0 * Eigen::Matrix3d::Identity();
  HapticContactFrame b = a;
  b.f_Tool_W = Eigen::Vector3d(0, 0, 2.0);
  b.p_Tool_W = Eigen::Vector3d(0, 0, -0.001);

  HapticForceRenderer r(0.005);
  const Eigen::Vector3d p(0.001, 0, 0);
  r.Update(a, p, 0.0);
  EXPECT_EQ(r.Force(p, 0.0), Eigen::Vector3d::Zero());  // a first touch fades in from nothing too
  EXPECT_TRUE(r.Force(p, 0.005).isApprox(RenderContactForce(a, p), 1e-15));
  r.Update(b, p, 0.01);
  EXPECT_TRUE(r.Force(p, 0.01).isApprox(RenderContactForce(a, p), 1e-15));  // no jump at the update
  const Eigen::Vector3d half = 0.5 * (RenderContactForce(a, p) + RenderContactForce(b, p));
  EXPECT_TRUE(r.Force(p, 0.0125).isApprox(half, 1e-12));                     // linear fade
  EXPECT_TRUE(r.Force(p, 0.015).isApprox(RenderContactForce(b, p), 1e-15));  // b after one blend time
  EXPECT_TRUE(r.Force(p, 1.0).isApprox(RenderContactForce(b, p), 1e-15));
  // Stiffness still acts during the fade: moving the tool changes the force at once.
  EXPECT_TRUE((r.Force(p + Eigen::Vector3d(0, 0, 0.001), 0.0125) - r.Force(p, 0.0125))
                  .isApprox(Eigen::Vector3d(0, 0, -0.1), 1e-12));
}

TEST(HapticForceRendererTest, RejectsANonPositiveBlendTime) {
  EXPECT_THROW(HapticForceRenderer(0.0), std::invalid_argument);
  EXPECT_THROW(HapticForceRenderer(std::numeric_limits<double>::quiet_NaN()), std::invalid_argument);
}

}  // namespace
}  // namespace vesica::physics
