#include "fx/smoke_emitter.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "fx/input_checks.h"

namespace vesica::fx {

namespace {
const std::string kOwner = "SmokeEmitter";
}  // namespace

SmokeEmitter::SmokeEmitter(const SmokeParams& params) : params_(params), rng_(params.seed) {
  CheckPositive(kOwner, "step_s", params.step_s);
  CheckPositive(kOwner, "emission_rate_per_s", params.emission_rate_per_s);
  CheckPositive(kOwner, "lifetime_s", params.lifetime_s);
  CheckFinite(kOwner, "rise_velocity_W", params.rise_velocity_W);
  CheckNonNegative(kOwner, "velocity_spread_mps", params.velocity_spread_mps);
  CheckPositive(kOwner, "initial_size_m", params.initial_size_m);
  CheckNonNegative(kOwner, "growth_mps", params.growth_mps);
  CheckPositive(kOwner, "initial_alpha", params.initial_alpha);
  if (params.initial_alpha > 1) throw std::invalid_argument(kOwner + ": initial_alpha must be <= 1");
  if (params.max_particles <= 0) {
    throw std::invalid_argument(kOwner + ": max_particles must be > 0, got " + std::to_string(params.max_particles));
  }
  particles_.reserve(static_cast<size_t>(params.max_particles));
}

double SmokeEmitter::UniformSymmetric() {
  // 53 random bits -> [0, 1), the same on every platform.
  const double u = static_cast<double>(rng_() >> 11) * 0x1.0p-53;
  return 2.0 * u - 1.0;
}

void SmokeEmitter::Update(double dt_s, bool active, const Eigen::Vector3d& p_Source_W) {
  CheckNonNegative(kOwner, "dt_s", dt_s);
  CheckFinite(kOwner, "p_Source_W", p_Source_W);
  carried_s_ += dt_s;
  // The small tolerance keeps a dt equal to step_s from losing a step to rounding.
  while (carried_s_ >= params_.step_s * (1 - 1e-9)) {
    carried_s_ = std::max(0.0, carried_s_ - params_.step_s);
    FixedStep(active, p_Source_W);
  }
}

void SmokeEmitter::FixedStep(bool active, const Eigen::Vector3d& p_Source_W) {
  const double h = params_.step_s;
  for (SmokeParticle& p : particles_) {
    p.age_s += h;
    p.p_W += h * p.v_W;
    p.size_m = params_.initial_size_m + params_.growth_mps * p.age_s;
    p.alpha = params_.initial_alpha * std::max(0.0, 1.0 - p.age_s / params_.lifetime_s);
  }
  // A particle is shown once with alpha 0 at the end of its life, then freed.
  std::erase_if(particles_, [&](const SmokeParticle& p) { return p.age_s > params_.lifetime_s; });

  if (!active) {
    pending_births_ = 0;  // a new burst starts afresh when the pedal goes down again
    return;
  }
  pending_births_ += params_.emission_rate_per_s * h;
  while (pending_births_ >= 1.0) {
    pending_births_ -= 1.0;
    if (static_cast<int>(particles_.size()) >= params_.max_particles) continue;  // pool full
    SmokeParticle p;
    p.p_W = p_Source_W;
    const double s = params_.velocity_spread_mps;
    const double kx = UniformSymmetric();
    const double ky = UniformSymmetric();
    const double kz = UniformSymmetric();
    p.v_W = params_.rise_velocity_W + s * Eigen::Vector3d(kx, ky, kz);
    p.age_s = 0;
    p.size_m = params_.initial_size_m;
    p.alpha = params_.initial_alpha;
    particles_.push_back(p);
  }
}

}  // namespace vesica::fx
