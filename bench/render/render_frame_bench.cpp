// What one trainer frame costs: the CPU side of LaparoscopeView::Update (organ vertices, normals,
// burn colours, membrane, smoke, instruments) and the whole frame (Update + draw + glFinish) in an
// off-screen window. Frames come from the committed dissection recording around 14 s (hook
// burning, grasper retracting, smoke), cycled so every Update really changes the arrays.
// Needs an X display: `xvfb-run -a build/release/bench/render/render_benchmark`. Under Xvfb the
// draw is Mesa's llvmpipe (software), which rasterises on its own worker threads: the wall time
// is the frame rate, and the "CPU" column is the main thread's own CPU time (Google Benchmark
// 1.7 reads CLOCK_THREAD_CPUTIME_ID of the benchmark's thread, not the process), which is what
// the trainer's render thread pays and what a GPU does not take away.
//
// For instruction counts (which a loaded host does not change), callgrind's instrumentation is
// switched on only around the timed frames: run it with `valgrind --tool=callgrind
// --instr-atstart=no --separate-threads=yes` (the 14 s replay before them runs uninstrumented).

#include <benchmark/benchmark.h>
#include <vtkNew.h>
#include <vtkRenderWindow.h>

#include <filesystem>
#include <memory>
#include <vector>

#if __has_include(<valgrind/callgrind.h>)
#include <valgrind/callgrind.h>  // no-ops outside valgrind
#else
#define CALLGRIND_START_INSTRUMENTATION
#define CALLGRIND_STOP_INSTRUMENTATION
#endif

#include "app/render/laparoscope_view.h"
#include "app/render/scene_meshes.h"
#include "app/replay/session_replay.h"
#include "app/scenario/scenario_loader.h"
#include "app/session/dissection_session.h"
#include "app/session/dissection_setup.h"
#include "device/input/input_recording.h"
#include "device/input/replay_input.h"
#include "physics/mesh/mesh_topology.h"

namespace {

using namespace vesica::app;

struct RenderFixture {
  Scenario scenario;
  SceneMeshes meshes;
  std::vector<RenderFrame> frames;
  std::unique_ptr<LaparoscopeView> view;
  // One window for the whole run, as the trainer keeps its window (a fresh X window per
  // benchmark run made Xvfb refuse the connection after a few).
  vtkNew<vtkRenderWindow> window;

  RenderFixture() : scenario(LoadScenario(DefaultScenarioPath())), meshes(LoadSceneMeshes(scenario)) {
    auto model = BuildDissectionModelFor(scenario, meshes);
    vesica::device::InputRecording rec =
        vesica::device::ReadInputRecording(std::filesystem::path(VESICA_SOURCE_DIR) / "data/recordings/dissection.csv");
    std::erase_if(rec.frames, [](const vesica::device::InputFrame& f) { return f.time_s > 14.0; });
    vesica::device::ReplayInput input(rec);
    DissectionSession session(model, DefaultCauteryParams());
    RunReplay(session, input, [&](const DissectionSession& s, const SessionStepReport&) {
      if (s.time_s() >= 13.0 && frames.size() < 16 && s.time_s() >= 13.0 + 0.05 * frames.size())
        frames.push_back(s.MakeRenderFrame());
    });
    view = std::make_unique<LaparoscopeView>(scenario, meshes);
    window->SetOffScreenRendering(1);
    window->SetMultiSamples(0);  // as the trainer's window (translucency under Mesa)
    window->SetAlphaBitPlanes(1);
    window->AddRenderer(view->renderer());
  }
};

RenderFixture& Fixture() {
  static RenderFixture fixture;
  return fixture;
}

void BM_ViewUpdate(benchmark::State& state) {
  RenderFixture& f = Fixture();
  std::size_t i = 0;
  for (auto _ : state) f.view->Update(f.frames[i++ % f.frames.size()]);
  state.counters["frames_cycled"] = static_cast<double>(f.frames.size());
}
BENCHMARK(BM_ViewUpdate)->Unit(benchmark::kMillisecond);

// The trainer's frame: Update, then draw into a window of the trainer's default size.
void BM_RenderFrame(benchmark::State& state) {
  RenderFixture& f = Fixture();
  vtkRenderWindow* window = f.window;
  window->SetSize(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  window->Render();  // the first frame at a size compiles shaders and allocates: not timed
  window->Render();
  std::size_t i = 0;
  CALLGRIND_START_INSTRUMENTATION;
  for (auto _ : state) {
    f.view->Update(f.frames[i++ % f.frames.size()]);
    window->Render();
    window->WaitForCompletion();
  }
  CALLGRIND_STOP_INSTRUMENTATION;
  state.counters["fps"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_RenderFrame)->Args({1280, 720})->Args({640, 360})->Unit(benchmark::kMillisecond)->UseRealTime();

// The same frame without the instruments' shadows: what the shadow's fragment-shader test costs.
// (VESICA_MATERIALS=phong runs both with the Phong fallback instead of PBR.)
void BM_RenderFrameWithoutShadows(benchmark::State& state) {
  Fixture().view->ShowInstrumentShadows(false);
  BM_RenderFrame(state);
  Fixture().view->ShowInstrumentShadows(true);
}
BENCHMARK(BM_RenderFrameWithoutShadows)->Args({1280, 720})->Unit(benchmark::kMillisecond)->UseRealTime();

// The same scene without the physics: the organs at rest, alternately 0.1 % larger (so every
// array really changes), the hook burning with 80 smoke puffs at the laparoscope's target and a
// 60-triangle membrane strip. It starts in a second instead of replaying 14 s of physics, which
// makes it the one to count instructions of (valgrind --tool=callgrind --instr-atstart=no
// --separate-threads=yes ... --benchmark_filter=Synthetic) and to compare changes by.
struct SyntheticFixture {
  Scenario scenario;
  SceneMeshes meshes;
  std::unique_ptr<LaparoscopeView> view;
  RenderFrame frames[2];
  vtkNew<vtkRenderWindow> window;

  SyntheticFixture() : scenario(LoadScenario(DefaultScenarioPath())), meshes(LoadSceneMeshes(scenario)) {
    view = std::make_unique<LaparoscopeView>(scenario, meshes);
    const auto gallbladder = vesica::physics::ExtractBoundary(meshes.gallbladder).surface;
    const Eigen::Vector3d target = scenario.laparoscope.look_at_m;
    for (int k = 0; k < 2; ++k) {
      RenderFrame& f = frames[k];
      const double scale = 1.0 + 1e-3 * k;
      f.liver_vertices = meshes.liver.vertices * scale;
      f.gallbladder_vertices = gallbladder.vertices * scale;
      f.liver_burn.assign(static_cast<std::size_t>(meshes.liver.num_triangles()), 0.0f);
      for (std::size_t t = 0; t < f.liver_burn.size(); t += 50) f.liver_burn[t] = 0.5f;
      // A strip of 60 triangles across the target, as the membrane's springs span the gap.
      f.membrane_vertices.resize(62, 3);
      for (int i = 0; i < 31; ++i)
        for (int side = 0; side < 2; ++side)
          f.membrane_vertices.row(2 * i + side) =
              (target + Eigen::Vector3d(0.001 * (i - 15), 0.004 * side - 0.002, 0.0005 * side)).transpose();
      f.membrane_triangles.resize(60, 3);
      for (int i = 0; i < 30; ++i) {
        f.membrane_triangles.row(2 * i) << 2 * i, 2 * i + 1, 2 * i + 2;
        f.membrane_triangles.row(2 * i + 1) << 2 * i + 1, 2 * i + 3, 2 * i + 2;
      }
      for (int i = 0; i < 80; ++i)
        f.smoke.push_back(
            {target + Eigen::Vector3d(0.0003 * (i % 9), 0.0004 * (i % 7), 0.0005 * i), 0.004 + 1e-4 * i, 0.25});
      for (const auto& pose : view->poses()) {
        InstrumentFrame instrument;
        instrument.pose = pose;
        instrument.pedal_down = instrument.cautery_active = true;
        f.instruments.push_back(instrument);
      }
      for (std::size_t i = 0; i < scenario.instruments.size(); ++i)
        f.instruments[i].tool = scenario.instruments[i].kind;
    }
    window->SetOffScreenRendering(1);
    window->SetMultiSamples(0);
    window->SetAlphaBitPlanes(1);
    window->AddRenderer(view->renderer());
  }
};

void BM_RenderSyntheticFrame(benchmark::State& state) {
  static SyntheticFixture f;
  f.window->SetSize(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  f.view->Update(f.frames[0]);
  f.window->Render();  // the first frame at a size compiles shaders and allocates: not timed
  f.window->Render();
  std::size_t i = 0;
  CALLGRIND_START_INSTRUMENTATION;
  for (auto _ : state) {
    f.view->Update(f.frames[i++ % 2]);
    f.window->Render();
    f.window->WaitForCompletion();
  }
  CALLGRIND_STOP_INSTRUMENTATION;
  state.counters["fps"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_RenderSyntheticFrame)->Args({1280, 720})->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
