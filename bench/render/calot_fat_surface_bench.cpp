// The Calot fat layer's surface on the main thread (issue 36; app/render/calot_fat_surface.h),
// with data/scenarios/calot-standard.toml's intact cells after one session step (no display):
//   BM_CalotFatSurfaceRebuild: a cell goes each frame (the hook burning): the surface is rebuilt;
//   BM_CalotFatSurfaceMove:    the cells move (the tubes pushed), the set unchanged: vertices move;
//   BM_CalotFatSurfaceSame:    nothing changed: the comparison only.
#include <benchmark/benchmark.h>

#include <memory>

#include "app/render/calot_fat_surface.h"
#include "app/render/display_frame.h"
#include "app/render/scene_meshes.h"
#include "app/scenario/scenario_loader.h"
#include "app/session/dissection_session.h"
#include "app/session/dissection_setup.h"

namespace vesica::app {
namespace {

struct Cells {
  std::vector<Eigen::Vector3d> rest_D, now_D;
  double cell_m = 0;
};

const Cells& StandardCells() {
  static const Cells cells = [] {
    const Scenario s = LoadScenario(DefaultScenarioPath().parent_path() / "calot-standard.toml");
    DissectionSession session(BuildDissectionModelFor(s, LoadSceneMeshes(s)), DefaultCauteryParams(),
                              CalotSessionSetupFor(s));
    session.Step(device::InputFrame{});
    const CalotDrawing d = CalotDrawingOf(*session.calot_step());
    Cells c;
    for (const Eigen::Vector3d& p : d.fat_cells_rest_W) c.rest_D.push_back(ToDisplay(p));
    for (const Eigen::Vector3d& p : d.fat_cells_W) c.now_D.push_back(ToDisplay(p));
    c.cell_m = d.fat_cell_size_m;
    return c;
  }();
  return cells;
}

void BM_CalotFatSurfaceRebuild(benchmark::State& state) {
  const Cells& all = StandardCells();
  CalotFatSurface surface;
  Cells fewer = all;
  fewer.rest_D.pop_back();
  fewer.now_D.pop_back();
  bool odd = false;
  for (auto _ : state) {
    const Cells& c = odd ? fewer : all;
    surface.Update(c.rest_D, c.now_D, c.cell_m);
    odd = !odd;
  }
  state.counters["cells"] = static_cast<double>(all.rest_D.size());
  state.counters["rebuilds"] = surface.rebuilds();
}
BENCHMARK(BM_CalotFatSurfaceRebuild)->Unit(benchmark::kMillisecond);

void BM_CalotFatSurfaceMove(benchmark::State& state) {
  const Cells& all = StandardCells();
  CalotFatSurface surface;
  Cells moved = all;
  for (Eigen::Vector3d& p : moved.now_D) p.z() += 0.0005;
  bool odd = false;
  for (auto _ : state) {
    const Cells& c = odd ? moved : all;
    surface.Update(c.rest_D, c.now_D, c.cell_m);
    odd = !odd;
  }
  state.counters["rebuilds"] = surface.rebuilds();
}
BENCHMARK(BM_CalotFatSurfaceMove)->Unit(benchmark::kMicrosecond);

void BM_CalotFatSurfaceSame(benchmark::State& state) {
  const Cells& all = StandardCells();
  CalotFatSurface surface;
  for (auto _ : state) surface.Update(all.rest_D, all.now_D, all.cell_m);
  state.counters["rebuilds"] = surface.rebuilds();
}
BENCHMARK(BM_CalotFatSurfaceSame)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace vesica::app
