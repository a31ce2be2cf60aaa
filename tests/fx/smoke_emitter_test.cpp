#include "fx/smoke_emitter.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <stdexcept>

namespace vesica::fx {
namespace {

using ::testing::HasSubstr;

// Step and lifetime are powers of two so ages add up exactly.
SmokeParams OnePerStep() {
  SmokeParams p;
  p.step_s = 1.0 / 64;
  p.emission_rate_per_s = 64;  // one particle per fixed step
  p.lifetime_s = 1.0;
  p.rise_velocity_W = Eigen::Vector3d(0, 0.02, 0);
  p.velocity_spread_mps = 0.004;
  p.initial_size_m = 0.002;
  p.growth_mps = 0.004;
  p.initial_alpha = 0.5;
  p.max_particles = 1000;
  p.seed = 42;
  return p;
}

// A replayable input: cautery on and off while the tip moves.
void Drive(SmokeEmitter& smoke) {
  for (int k = 0; k < 300; ++k) {
    const bool active = (k / 40) % 2 == 0;
    const Eigen::Vector3d tip(0.001 * std::sin(0.1 * k), 0.05, 0.0005 * k);
    smoke.Update(k % 3 == 0 ? 0.01 : 0.02, active, tip);
  }
}

bool BitIdentical(const std::vector<SmokeParticle>& a, const std::vector<SmokeParticle>& b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i) {
    const double x[] = {a[i].p_W.x(), a[i].p_W.y(), a[i].p_W.z(), a[i].v_W.x(), a[i].v_W.y(),
                        a[i].v_W.z(), a[i].age_s,   a[i].size_m,  a[i].alpha};
    const double y[] = {b[i].p_W.x(), b[i].p_W.y(), b[i].p_W.z(), b[i].v_W.x(), b[i].v_W.y(),
                        b[i].v_W.z(), b[i].age_s,   b[i].size_m,  b[i].alpha};
    if (std::memcmp(x, y, sizeof(x)) != 0) return false;
  }
  return true;
}

TEST(SmokeEmitterTest, TwoRunsWithTheSameSeedAndInputAreBitIdentical) {
  SmokeEmitter a(OnePerStep()), b(OnePerStep());
  Drive(a);
  Drive(b);
  ASSERT_FALSE(a.particles().empty());
  EXPECT_TRUE(BitIdentical(a.particles(), b.particles()));

  SmokeParams other = OnePerStep();
  other.seed = 43;
  SmokeEmitter c(other);
  Drive(c);
  EXPECT_FALSE(BitIdentical(a.particles(), c.particles())) << "the seed has no effect";
}

TEST(SmokeEmitterTest, NothingIsEmittedWhileInactive) {
  SmokeEmitter smoke(OnePerStep());
  for (int k = 0; k < 200; ++k) smoke.Update(0.01, false, Eigen::Vector3d(0, 0, 0));
  EXPECT_TRUE(smoke.particles().empty());
}

TEST(SmokeEmitterTest, AlphaDecaysLinearlyToZeroAtEndOfLifeThenTheParticleIsFreed) {
  const SmokeParams p = OnePerStep();
  SmokeEmitter smoke(p);
  const Eigen::Vector3d tip(0.01, 0.02, 0.03);
  smoke.Update(p.step_s, true, tip);  // exactly one fixed step: one newborn particle
  ASSERT_EQ(smoke.particles().size(), 1u);
  EXPECT_EQ(smoke.particles()[0].p_W, tip);
  EXPECT_EQ(smoke.particles()[0].alpha, p.initial_alpha);
  EXPECT_EQ(smoke.particles()[0].size_m, p.initial_size_m);

  double previous_alpha = p.initial_alpha;
  for (int k = 1; k <= 64; ++k) {
    smoke.Update(p.step_s, false, tip);
    ASSERT_EQ(smoke.particles().size(), 1u) << "step " << k;
    const SmokeParticle& s = smoke.particles()[0];
    EXPECT_EQ(s.age_s, k * p.step_s);
    EXPECT_DOUBLE_EQ(s.alpha, p.initial_alpha * (1 - k / 64.0));
    EXPECT_LT(s.alpha, previous_alpha);
    EXPECT_DOUBLE_EQ(s.size_m, p.initial_size_m + p.growth_mps * s.age_s);
    previous_alpha = s.alpha;
  }
  EXPECT_EQ(smoke.particles()[0].alpha, 0.0);  // end of life: fully transparent
  smoke.Update(p.step_s, false, tip);
  EXPECT_TRUE(smoke.particles().empty());
}

TEST(SmokeEmitterTest, ParticlesRiseWithABoundedSpread) {
  const SmokeParams p = OnePerStep();
  SmokeEmitter smoke(p);
  const Eigen::Vector3d tip(0, 0, 0);
  smoke.Update(0.5, true, tip);
  ASSERT_EQ(smoke.particles().size(), 32u);
  bool spread_seen = false;
  for (const SmokeParticle& s : smoke.particles()) {
    const Eigen::Vector3d kick = s.v_W - p.rise_velocity_W;
    EXPECT_LE(kick.cwiseAbs().maxCoeff(), p.velocity_spread_mps);
    EXPECT_GT(s.v_W.y(), 0.0);
    EXPECT_GE(s.p_W.y(), 0.0);
    spread_seen = spread_seen || kick.norm() > 0;
  }
  EXPECT_TRUE(spread_seen);
}

TEST(SmokeEmitterTest, PoolStaysBounded) {
  SmokeParams p = OnePerStep();
  p.emission_rate_per_s = 10000;
  p.max_particles = 10;
  SmokeEmitter smoke(p);
  for (int k = 0; k < 500; ++k) {
    smoke.Update(0.013, true, Eigen::Vector3d(0, 0, 0));
    ASSERT_LE(smoke.particles().size(), 10u);
  }
  EXPECT_EQ(smoke.particles().size(), 10u);
}

TEST(SmokeEmitterTest, SplittingAStepDoesNotChangeTheResult) {
  SmokeEmitter whole(OnePerStep()), split(OnePerStep());
  for (int k = 0; k < 50; ++k) {
    whole.Update(1.0 / 32, true, Eigen::Vector3d(0, 0, 0.001 * k));
    split.Update(1.0 / 64, true, Eigen::Vector3d(0, 0, 0.001 * k));
    split.Update(1.0 / 64, true, Eigen::Vector3d(0, 0, 0.001 * k));
  }
  EXPECT_TRUE(BitIdentical(whole.particles(), split.particles()));
}

TEST(SmokeEmitterTest, RejectsBadInput) {
  SmokeEmitter smoke(OnePerStep());
  EXPECT_THAT([&] { smoke.Update(-0.01, true, Eigen::Vector3d::Zero()); },
              ::testing::ThrowsMessage<std::invalid_argument>(HasSubstr("SmokeEmitter: dt_s")));
  EXPECT_THAT([&] { smoke.Update(0.01, true, Eigen::Vector3d(0, std::nan(""), 0)); },
              ::testing::ThrowsMessage<std::invalid_argument>(HasSubstr("SmokeEmitter: p_Source_W is not finite")));
  EXPECT_TRUE(smoke.particles().empty());
  SmokeParams bad = OnePerStep();
  bad.max_particles = 0;
  EXPECT_THAT([&] { SmokeEmitter s(bad); },
              ::testing::ThrowsMessage<std::invalid_argument>(HasSubstr("max_particles")));
}

}  // namespace
}  // namespace vesica::fx
