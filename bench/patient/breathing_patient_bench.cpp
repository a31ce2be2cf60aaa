// The breathing patient (issue 33): one respiration update of the whole patient (target <= 1 ms on
// one core, for the next issue's 1 kHz haptic loop), and loading + meshing the committed synthetic
// patient (target <= 10 s).
#include <benchmark/benchmark.h>

#include <filesystem>

#include "app/patient/patient_files.h"
#include "app/patient/patient_meshing.h"
#include "physics/patient/breathing_patient.h"
#include "physics/patient/breathing_patient_model.h"

namespace {
namespace fs = std::filesystem;
namespace patient = vesica::app::patient;
using vesica::physics::BreathingPatient;

const fs::path kData = fs::path(VESICA_SOURCE_DIR) / "data" / "patients";

patient::PatientVolume LoadCommitted() {
  return patient::LoadNiftiPatient(kData / "synthetic-biopsy_ct.nii.gz", kData / "synthetic-biopsy_labels.nii.gz",
                                   kData / "synthetic-biopsy_labels.toml");
}

const std::shared_ptr<const vesica::physics::BreathingPatientModel>& Model() {
  static const auto model = vesica::physics::BuildBreathingPatientModel(LoadCommitted().labels);
  return model;
}

// Ribs, diaphragm and liver for one time, stepping at the haptic rate through whole breaths.
void BM_RespirationUpdate(benchmark::State& state) {
  BreathingPatient breathing(Model());
  double t = 0.0;
  for (auto _ : state) {
    t += 0.001;
    breathing.Update(t);
    benchmark::DoNotOptimize(breathing.snapshot().liver_m.data());
  }
  state.counters["liver_elements"] = Model()->liver.lattice.size();
  state.counters["diaphragm_elements"] = Model()->diaphragm.lattice.size();
}
BENCHMARK(BM_RespirationUpdate)->Unit(benchmark::kMicrosecond);

// The same with the snapshot handed to the renderer and the haptic loop.
void BM_RespirationUpdateAndPublish(benchmark::State& state) {
  BreathingPatient breathing(Model());
  double t = 0.0;
  for (auto _ : state) {
    t += 0.001;
    breathing.Update(t);
    breathing.Publish();
  }
}
BENCHMARK(BM_RespirationUpdateAndPublish)->Unit(benchmark::kMicrosecond);

// With a needle pushing the capsule (the next issue's case).
void BM_RespirationUpdateWithCapsulePush(benchmark::State& state) {
  BreathingPatient breathing(Model());
  breathing.Update(0.0);
  const Eigen::Vector3d tip = breathing.snapshot().liver_m[static_cast<std::size_t>(Model()->liver.capsule.front())];
  breathing.PushCapsule(tip, Eigen::Vector3d(0.004, 0.0, 0.0));
  double t = 0.0;
  for (auto _ : state) {
    t += 0.001;
    breathing.Update(t);
  }
}
BENCHMARK(BM_RespirationUpdateWithCapsulePush)->Unit(benchmark::kMicrosecond);

void BM_LoadPatient(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(LoadCommitted().hu.data());
}
BENCHMARK(BM_LoadPatient)->Unit(benchmark::kMillisecond)->Iterations(3);

void BM_BuildBreathingModel(benchmark::State& state) {
  const patient::PatientVolume volume = LoadCommitted();
  for (auto _ : state) benchmark::DoNotOptimize(vesica::physics::BuildBreathingPatientModel(volume.labels).get());
}
BENCHMARK(BM_BuildBreathingModel)->Unit(benchmark::kMillisecond)->Iterations(3);

void BM_MeshPatient(benchmark::State& state) {
  const patient::PatientVolume volume = LoadCommitted();
  for (auto _ : state) benchmark::DoNotOptimize(patient::MeshPatient(volume.labels).size());
}
BENCHMARK(BM_MeshPatient)->Unit(benchmark::kMillisecond)->Iterations(2);

// Everything a session start needs: files, model, meshes.
void BM_LoadAndMeshPatient(benchmark::State& state) {
  for (auto _ : state) {
    const patient::PatientVolume volume = LoadCommitted();
    const auto model = vesica::physics::BuildBreathingPatientModel(volume.labels);
    benchmark::DoNotOptimize(patient::MeshPatient(volume.labels).size());
    benchmark::DoNotOptimize(model.get());
  }
}
BENCHMARK(BM_LoadAndMeshPatient)->Unit(benchmark::kMillisecond)->Iterations(2);

}  // namespace
