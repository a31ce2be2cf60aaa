// The dissection session's step with Calot's triangle (issue 36: the scene step with the
// triangle's tubes and fat layer within the dissection's 3 ms on one core). The default scenario
// with data/scenarios/calot-standard.toml's triangle; the hook held on the triangle's fat with its
// pedal down (the fat burns, the tip pushes the tubes), the grasper out of the field. Also the
// same session without the triangle, and the triangle's own step (CalotTriangleStep) alone.
#include <benchmark/benchmark.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "app/render/scene_meshes.h"
#include "app/scenario/scenario_loader.h"
#include "app/session/dissection_session.h"
#include "app/session/dissection_setup.h"
#include "physics/instrument/instrument_pose.h"

namespace vesica::app {
namespace {


struct Setup {
  Scenario scenario;
  std::shared_ptr<const physics::DissectionModel> model;
};

const Setup& TheSetup() {
  static const Setup setup = [] {
    // The committed standard variant: the usual triangle on the default scenario's organs.
    Setup s{LoadScenario(DefaultScenarioPath().parent_path() / "calot-standard.toml"), nullptr};
    s.model = BuildDissectionModelFor(s.scenario, LoadSceneMeshes(s.scenario));
    return s;
  }();
  return setup;
}

// The hook on the triangle's fat (the slab's middle), pedal down.
device::InputFrame HookOnTheFat(const DissectionSession& session, const physics::DissectionModel& model) {
  const auto& description = session.calot_tubes()->description();
  const Eigen::Vector3d target =
      (description.tubes[0].centreline_m.front() + description.p_Neck_W_m + description.tubes[2].centreline_m.front()) /
      3.0;
  const physics::InstrumentMount& mount = model.instruments[1];
  device::InputFrame f;
  f.right_tool = physics::InstrumentTool::kCauteryHook;
  f.instruments[1].pose = physics::AimAt(mount.p_RemoteCentre_W, target, (target - mount.p_RemoteCentre_W).norm(),
                                         mount.reference_direction_W);
  f.instruments[1].pedal = true;
  return f;
}

void BM_SessionStepWithoutTriangle(benchmark::State& state) {
  const Setup& s = TheSetup();
  DissectionSession session(s.model, DefaultCauteryParams());
  DissectionSession with(s.model, DefaultCauteryParams(), CalotSessionSetupFor(s.scenario));
  const device::InputFrame frame = HookOnTheFat(with, *s.model);  // the same hands
  for (auto _ : state) benchmark::DoNotOptimize(session.Step(frame));
}
BENCHMARK(BM_SessionStepWithoutTriangle)->Unit(benchmark::kMillisecond)->Iterations(400);

void BM_SessionStepWithTriangle(benchmark::State& state) {
  const Setup& s = TheSetup();
  DissectionSession session(s.model, DefaultCauteryParams(), CalotSessionSetupFor(s.scenario));
  const device::InputFrame frame = HookOnTheFat(session, *s.model);
  for (auto _ : state) benchmark::DoNotOptimize(session.Step(frame));
  state.counters["fat_burnt"] = session.calot_fat()->BurntFraction();
}
BENCHMARK(BM_SessionStepWithTriangle)->Unit(benchmark::kMillisecond)->Iterations(400);

// The triangle's share alone: CalotTriangleStep::Step on a session's scene; the argument is the
// visibility's refresh period in steps (1: every step, the refreshing step's cost).
void BM_CalotTriangleStepAlone(benchmark::State& state) {
  const Setup& s = TheSetup();
  DissectionSession session(s.model, DefaultCauteryParams(), CalotSessionSetupFor(s.scenario));
  const device::InputFrame frame = HookOnTheFat(session, *s.model);
  session.Step(frame);
  CalotToolGeometry geometry;
  geometry.visibility_period_steps = static_cast<int>(state.range(0));
  CalotTriangleStep step(*CalotSessionSetupFor(s.scenario), session.scene(), geometry);
  for (auto _ : state) {
    step.Step(session.scene(), frame, true);
    benchmark::DoNotOptimize(step.last_snapshot().fat_removed_fraction);
  }
  state.counters["fat_burnt"] = step.fat().BurntFraction();
}
BENCHMARK(BM_CalotTriangleStepAlone)->Arg(10)->Arg(1)->Unit(benchmark::kMicrosecond)->Iterations(2000);

}  // namespace
}  // namespace vesica::app
