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

constexpr const char* kTriangle = R"(
[calot_triangle]
variant = "standard"
neck_m = [-0.0173, -0.0267, 0.0453]
[[calot_triangle.tubes]]
name = "cystic duct"
kind = "cystic_duct"
points_m = [[-0.0034, -0.0635, 0.0273], [-0.0124, -0.0471, 0.0359], [-0.0173, -0.0267, 0.0453]]
[[calot_triangle.tubes]]
name = "cystic artery"
kind = "cystic_artery"
points_m = [[0.0174, -0.0369, 0.0529], [0.0009, -0.0365, 0.0433], [-0.0207, -0.0239, 0.0422]]
[[calot_triangle.tubes]]
name = "common hepatic duct"
kind = "common_hepatic_duct"
points_m = [[0.0210, -0.0375, 0.0555], [0.0149, -0.0525, 0.0411], [-0.0034, -0.0635, 0.0273]]
[[calot_triangle.tubes]]
name = "common bile duct"
kind = "common_bile_duct"
points_m = [[-0.0034, -0.0635, 0.0273], [-0.0078, -0.0778, 0.0145], [-0.0089, -0.0983, -0.0066]]
)";

struct Setup {
  Scenario scenario;
  std::shared_ptr<const physics::DissectionModel> model;
};

const Setup& TheSetup() {
  static const Setup setup = [] {
    std::ifstream in(DefaultScenarioPath());
    std::string text((std::istreambuf_iterator<char>(in)), {});
    const std::filesystem::path dir = DefaultScenarioPath().parent_path();
    for (std::size_t at = 0; (at = text.find("\"../", at)) != std::string::npos;)
      text.replace(at + 1, 3, (dir / "..").string() + "/");
    const std::filesystem::path file = std::filesystem::temp_directory_path() / "vesica_calot_session_bench.toml";
    std::ofstream(file) << text << kTriangle;
    Setup s{LoadScenario(file), nullptr};
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
