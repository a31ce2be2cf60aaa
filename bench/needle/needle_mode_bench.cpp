// What one frame of the trainer's needle mode costs (issue 34; the biopsy paper drew at 20 Hz):
// the 3D patient's update (organs moved with the breathing, the needle), the two CT guidance
// images resliced through the breathing (done at 10 Hz), and a whole frame (update + draw +
// glFinish) in an off-screen window of the trainer's size. The states come from the committed
// recorded biopsy, every 50 ms of it, cycled.
// Needs an X display: `xvfb-run -a build/release/bench/needle/needle_mode_benchmark`. Under Xvfb
// the draw is Mesa's llvmpipe (software, threaded): wall time is the frame rate; CPU time is the
// main thread's.

#include <benchmark/benchmark.h>
#include <vtkNew.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>

#include <cstdio>
#include <filesystem>
#include <memory>
#include <vector>

#include "app/biopsy/biopsy_session.h"
#include "app/biopsy/ct_slice.h"
#include "app/needle_mode/patient_view.h"
#include "device/stylus/replay_stylus.h"

namespace {

using namespace vesica::app;

struct NeedleModeFixture {
  std::shared_ptr<const biopsy::BiopsyPatient> patient;
  std::vector<vesica::physics::PatientSnapshot> patients;
  std::vector<biopsy::NeedleFrame> needles;
  std::unique_ptr<needle_mode::PatientView> view;
  vtkNew<vtkRenderWindow> window;
  long triangles = 0;

  NeedleModeFixture()
      : patient(biopsy::LoadCommittedBiopsyPatient(std::filesystem::path(VESICA_SOURCE_DIR) / "data/patients")) {
    const vesica::device::ReplayStylus stylus(
        vesica::device::ReadStylusRecording(std::filesystem::path(VESICA_SOURCE_DIR) / "data/recordings/biopsy.csv"));
    biopsy::BiopsySession session(patient);
    for (int k = 0; k <= 12000; ++k) {
      const double t = k * 0.001;
      const auto& forces = session.Tick(stylus.SampleAt(t), t);
      if (k % 50 != 0) continue;
      patients.push_back(session.patient().snapshot());
      biopsy::NeedleFrame frame;
      frame.pose = session.needle_pose();
      frame.inside = forces.inside;
      needles.push_back(frame);
    }
    auto surfaces = patient::MeshPatient(patient->volume.labels, needle_mode::DisplayMeshing());
    for (const auto& s : surfaces) triangles += s.mesh.num_triangles();
    view = std::make_unique<needle_mode::PatientView>(*patient, std::move(surfaces));
    window->SetOffScreenRendering(1);
    window->SetMultiSamples(0);
    window->SetAlphaBitPlanes(1);
    window->AddRenderer(view->renderer());
  }
};

NeedleModeFixture& Fixture() {
  static NeedleModeFixture fixture;
  return fixture;
}

void BM_PatientViewUpdate(benchmark::State& state) {
  NeedleModeFixture& f = Fixture();
  std::size_t i = 0;
  for (auto _ : state) {
    f.view->Update(f.patients[i % f.patients.size()], f.needles[i % f.needles.size()]);
    ++i;
  }
}
BENCHMARK(BM_PatientViewUpdate)->Unit(benchmark::kMillisecond);

// Both guidance images (160 x 160 pixels of 1.5 mm each), as the window reslices them.
void BM_GuidanceSlices(benchmark::State& state) {
  NeedleModeFixture& f = Fixture();
  vesica::physics::DeformedCt ct(f.patient->ct);
  std::size_t i = 0;
  for (auto _ : state) {
    const auto& needle = f.needles[i % f.needles.size()];
    ct.SetPatient(f.patients[i % f.patients.size()]);
    ct.SetBlend(1.0);
    benchmark::DoNotOptimize(biopsy::SampleSlice(ct, biopsy::AxialSliceThrough(needle.pose.tip_m)));
    benchmark::DoNotOptimize(biopsy::SampleSlice(ct, biopsy::ObliqueSliceAlong(needle.pose)));
    ++i;
  }
}
BENCHMARK(BM_GuidanceSlices)->Unit(benchmark::kMillisecond);

// The needle mode's 3D frame: update, then draw into a window of the given size.
void BM_NeedleModeFrame(benchmark::State& state) {
  NeedleModeFixture& f = Fixture();
  vtkRenderWindow* window = f.window;
  window->SetSize(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  window->Render();  // the first frame at a size compiles shaders and allocates: not timed
  std::size_t i = 0;
  for (auto _ : state) {
    f.view->Update(f.patients[i % f.patients.size()], f.needles[i % f.needles.size()]);
    window->Render();
    window->WaitForCompletion();
    ++i;
  }
  state.counters["fps"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["triangles"] = static_cast<double>(f.triangles);
}
BENCHMARK(BM_NeedleModeFrame)->Args({640, 720})->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
