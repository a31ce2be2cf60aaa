// The needle's force update per haptic tick with respiration on (issue 34; target <= 50 us on one
// core at 1 kHz). The patient breathes at 0.25 Hz and publishes every 20 ms (its update runs on
// the physics thread and is not counted); each tick here is what the haptic thread does: take a
// new snapshot when one has come (every 20th tick) and compute the needle's force.
#include <benchmark/benchmark.h>

#include <memory>
#include <vector>

#include "app/patient/synthetic_patient.h"
#include "physics/needle/needle_haptics.h"
#include "physics/patient/breathing_patient.h"

namespace {
using namespace vesica::physics;

struct Setup {
  std::shared_ptr<const BreathingPatientModel> model;
  std::shared_ptr<const DeformedCtModel> ct;
  std::vector<PatientSnapshot> breath;  // one breath, a snapshot every 20 ms
};
const Setup& Get() {
  static const Setup setup = [] {
    Setup s;
    const auto volume = vesica::app::patient::GenerateSyntheticPatient();
    s.model = BuildBreathingPatientModel(volume.labels);
    s.ct = BuildDeformedCtModel(s.model, volume.hu);
    BreathingPatient patient(s.model);
    for (int k = 0; k < 200; ++k) {
      patient.Update(0.02 * k);
      s.breath.push_back(patient.snapshot());
    }
    return s;
  }();
  return setup;
}

// Inserts the needle from start along direction by length (1 mm a tick, patient at rest).
NeedleHaptics Inserted(const Eigen::Vector3d& start, const Eigen::Vector3d& direction, double length, double& t) {
  NeedleHaptics needle(Get().ct);
  for (double s = 0.0; s <= length; s += 0.001) needle.Update({start + s * direction, direction}, t += 0.001);
  return needle;
}

void Tick(benchmark::State& state, const Eigen::Vector3d& start, const Eigen::Vector3d& direction, double length) {
  double t = 0.0;
  NeedleHaptics needle = Inserted(start, direction, length, t);
  const Eigen::Vector3d tip = start + length * direction;
  std::size_t tick = 0;
  double hu = 0.0;
  for (auto _ : state) {
    t += 0.001;
    if (tick % 20 == 0) needle.SetPatient(Get().breath[(tick / 20) % Get().breath.size()], t);
    // A hand's tremor of a tenth of a millimetre.
    const Eigen::Vector3d tremor(1e-4 * ((tick % 7) / 6.0 - 0.5), 0.0, 1e-4 * ((tick % 5) / 4.0 - 0.5));
    const NeedleForces& f = needle.Update({tip + tremor, direction}, t);
    benchmark::DoNotOptimize(f.total_N.data());
    hu = f.hu_crossed;
    ++tick;
  }
  state.counters["inside_mm"] = 1e3 * needle.forces().inserted_m;
  state.counters["hu_crossed"] = hu;
}

// Anterior, into the tumour's centre: 80 mm of needle in the body, through the capsule.
void BM_NeedleTickTumour(benchmark::State& state) { Tick(state, {-0.075, 0.14, -0.045}, {0.0, -1.0, 0.0}, 0.12); }
BENCHMARK(BM_NeedleTickTumour)->Unit(benchmark::kMicrosecond);

// From the right flank through rib 9, the diaphragm's edge and the liver: 120 mm in the body, near
// the moving ribs and both lattices.
void BM_NeedleTickFlank(benchmark::State& state) {
  const Eigen::Vector3d start(-0.20, 0.02, -0.06), to(-0.075, 0.02, -0.045);
  Tick(state, start, (to - start).normalized(), 0.16);
}
BENCHMARK(BM_NeedleTickFlank)->Unit(benchmark::kMicrosecond);

// Adopting a new patient snapshot alone (once per physics update on the haptic thread).
void BM_NeedleSetPatient(benchmark::State& state) {
  NeedleHaptics needle(Get().ct);
  std::size_t k = 0;
  double t = 0.0;
  for (auto _ : state) needle.SetPatient(Get().breath[k++ % Get().breath.size()], t += 0.02);
}
BENCHMARK(BM_NeedleSetPatient)->Unit(benchmark::kMicrosecond);

}  // namespace
