#pragma once
// Cautery smoke (paper §2.5.3: smoke sprites with changing positions and decreasing alpha) as
// a bounded particle pool advanced on a fixed step. Deterministic under replay: the only
// randomness is a seeded 64-bit generator held in the emitter, turned into doubles by bit
// arithmetic (std:: distributions differ between standard libraries).

#include <Eigen/Core>
#include <cstdint>
#include <random>
#include <vector>

namespace vesica::fx {

struct SmokeParams {
  double step_s = 1.0 / 120.0;                                    ///< fixed update step, seconds, > 0
  double emission_rate_per_s = 60;                                ///< particles per second while cautery is active, > 0
  double lifetime_s = 1.5;                                        ///< age at which alpha reaches 0, seconds, > 0
  Eigen::Vector3d rise_velocity_W = Eigen::Vector3d(0, 0.02, 0);  ///< m/s; +y is anterior (up)
  double velocity_spread_mps = 0.004;  ///< each component gets a uniform kick in [-s, s], >= 0
  double initial_size_m = 0.002;       ///< sprite size at birth, > 0
  double growth_mps = 0.004;           ///< size gained per second of life, >= 0
  double initial_alpha = 0.6;          ///< alpha at birth, in (0, 1]
  int max_particles = 256;             ///< pool size; emission pauses while it is full, > 0
  std::uint64_t seed = 1;
};

struct SmokeParticle {
  Eigen::Vector3d p_W;  ///< position, metres
  Eigen::Vector3d v_W;  ///< velocity, m/s
  double age_s = 0;
  double size_m = 0;
  double alpha = 0;  ///< initial_alpha * (1 - age / lifetime): 0 at end of life
};

class SmokeEmitter {
 public:
  explicit SmokeEmitter(const SmokeParams& params);

  /// Advances by dt_s (carried over in fixed steps). While `active`, particles are born at
  /// p_Source_W (the hook contact) at emission_rate_per_s. Throws for negative/non-finite dt
  /// or a non-finite source.
  void Update(double dt_s, bool active, const Eigen::Vector3d& p_Source_W);

  /// Live particles, oldest first: what the renderer reads.
  const std::vector<SmokeParticle>& particles() const { return particles_; }
  const SmokeParams& params() const { return params_; }

 private:
  void FixedStep(bool active, const Eigen::Vector3d& p_Source_W);
  double UniformSymmetric();  ///< in [-1, 1)

  SmokeParams params_;
  std::mt19937_64 rng_;
  std::vector<SmokeParticle> particles_;
  double carried_s_ = 0;       ///< time not yet consumed by a fixed step
  double pending_births_ = 0;  ///< fractional particles owed by the emission rate
};

}  // namespace vesica::fx
