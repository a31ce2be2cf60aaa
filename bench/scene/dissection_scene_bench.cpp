// The coupled cholecystectomy scene step (issue 6) at the spec's sizes, and the force update the
// 1 kHz device loop calls. Scene: tests/scene/synthetic_dissection.h's liver box and gallbladder
// box, refined here:
//   liver: the 80 x 40 x 60 mm box with 17 x 9 x 13 cells -> 984 BEM surface nodes, top face fixed,
//          bottom face the gallbladder bed;
//   gallbladder: the 30 x 20 x 30 mm box with 13 x 4 x 13 cells (980 nodes) or 13 x 14 x 13 cells
//          (2,940 nodes): a 14 x 14 top face -> 196 springs for both sizes;
//   material and solver: the default scenario (data/scenarios/cholecystectomy.toml): gallbladder
//          corotational, E 2300 Pa, nu 0.45, Rayleigh 0.1 /s and 0.01 s; liver E 170 kPa, nu 0.4.
// Both tools are in contact in every timed step: the grasper holds the gallbladder's bottom face
// and pulls 2 mm down with a +-0.5 mm, 0.5 s sway; the hook presses 1 mm into the gallbladder's
// bottom face (hook arg 0) or into the liver's bed beside the gallbladder (hook arg 1).
//   BM_DissectionStep/<gb nodes>/<solver>/<hook: 0 gallbladder, 1 liver>, solver: 0 PCG (20
//     iterations, block Jacobi; the scenario's default), 1 CHOLMOD (refactorised every step),
//     2 kRotatedFactorPcg with rotated_factor_gauss_seidel (float rest factor turned per node,
//     wrapped in block Gauss-Seidel sweeps; converges to pcg_relative_tolerance 1e-8, cap 20)
//     time = DissectionScene::Step wall time; counters = mean per-stage times of
//     DissectionStepReport::times (us; "frames_us" = total - sum of stages: haptic frames,
//     touches, membrane), sizes, constraint rows and the fraction of steps with both tools in contact.
//     No PCG-iteration counter: DissectionStepReport does not carry the gallbladder's
//     FemBody::StepReport (solver_iterations, relative_residual), and DissectionScene::gallbladder()
//     is const; docs/performance/scene.md gives the counts from a diagnostic build.
//   BM_HapticForceUpdate: one 1 ms device tick: HapticForceRenderer::Update with a new physics
//     frame every 5th tick (200 Hz physics), Force every tick.
//   BM_RenderContactForce: RenderContactForce on a unilateral (hook) frame.
//   BM_FreedGallbladderResting/<contact 0|1>: the freed box falling freely (0) or lying on an
//     ellipsoid (1), issue 30's static obstacles; counters: rows, pressed nodes, two stage times,
//     Gauss-Seidel sweeps of the constraint solve.
// Models (BEM pre-process: seconds) and warmed-up scenes are built once per size, outside the
// timed loops; the liver's Green's functions are cached in $TMPDIR across runs.

#include <benchmark/benchmark.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <map>
#include <memory>
#include <numbers>
#include <stdexcept>
#include <string>
#include <tuple>

#include "physics/mesh/primitives.h"
#include "physics/scene/dissection_scene.h"
#include "physics/scene/haptic_contact_frame.h"
#include "physics/scene/haptic_force_renderer.h"
#include "tests/scene/synthetic_dissection.h"

namespace vesica::physics {
namespace {

using testing::kGallbladderBottomInsertion;

constexpr int kGallbladderSmallNodes = 980;   // 14 x 5 x 14
constexpr int kGallbladderLargeNodes = 2940;  // 14 x 15 x 14

int GallbladderLayers(int nodes) {
  if (nodes == kGallbladderSmallNodes) return 4;
  if (nodes == kGallbladderLargeNodes) return 14;
  throw std::invalid_argument("scene bench: no gallbladder box with " + std::to_string(nodes) + " nodes");
}

// The solver argument of BM_DissectionStep.
enum SolverArg : int { kSolverPcg = 0, kSolverCholmod = 1, kSolverRotatedFactorGs = 2 };

void SetSolver(FemSettings& gallbladder, int solver) {
  switch (solver) {
    case kSolverPcg:
      gallbladder.solver = LinearSolverKind::kPcg;
      return;
    case kSolverCholmod:
      gallbladder.solver = LinearSolverKind::kCholmod;
      return;
    case kSolverRotatedFactorGs:
      gallbladder.solver = LinearSolverKind::kRotatedFactorPcg;
      gallbladder.rotated_factor_gauss_seidel = true;
      return;
  }
  throw std::invalid_argument("scene bench: no solver argument " + std::to_string(solver));
}

DissectionModelInputs SceneInputs(int gallbladder_nodes, int solver) {
  DissectionModelInputs in = testing::SyntheticDissectionInputs();
  // Liver: same box and labels as the synthetic scene, 984 surface nodes.
  in.liver_surface = ExtractBoundary(MakeBoxTetMesh({0.08, 0.04, 0.06}, {17, 9, 13})).surface;
  in.liver_surface.vertices.rowwise() += Eigen::RowVector3d(-0.04 + testing::kShiftX, 0.0, -0.03 + testing::kShiftZ);
  in.liver_surface.vertex_labels = Eigen::VectorXi::Zero(in.liver_surface.num_vertices());
  for (int v = 0; v < in.liver_surface.num_vertices(); ++v) {
    const double y = in.liver_surface.vertices(v, 1);
    if (y > 0.04 - 1e-9) in.liver_surface.vertex_labels[v] = kLabelFixed;
    if (y < 1e-9) in.liver_surface.vertex_labels[v] = kLabelGallbladderBed;
  }
  in.liver_source = "scene bench liver box";
  in.liver_material = {170e3, 0.4, 1060.0};
  in.liver_bem.cache_path = (std::filesystem::temp_directory_path() / "vesica_scene_bench_liver_984.bin").string();

  // Gallbladder: same box, 14 x 14 top vertices (196 springs), refined through its depth.
  in.gallbladder_mesh = MakeBoxTetMesh({0.03, 0.02, 0.03}, {13, GallbladderLayers(gallbladder_nodes), 13});
  in.gallbladder_mesh.vertices.rowwise() +=
      Eigen::RowVector3d(-0.015 + testing::kShiftX, testing::kGallbladderBottomY, -0.015 + testing::kShiftZ);
  in.gallbladder_source = "scene bench gallbladder box";
  in.gallbladder.material = {2300.0, 0.45, 1000.0};
  in.gallbladder.element_model = ElementModel::kCorotational;
  SetSolver(in.gallbladder, solver);
  in.gallbladder.rayleigh_mass_per_s = 0.1;
  in.gallbladder.rayleigh_stiffness_s = 0.01;
  return in;
}

std::shared_ptr<const DissectionModel> CachedModel(int gallbladder_nodes, int solver) {
  static std::map<std::pair<int, int>, std::shared_ptr<const DissectionModel>> models;
  auto& model = models[{gallbladder_nodes, solver}];
  if (!model) model = BuildDissectionModel(SceneInputs(gallbladder_nodes, solver));
  return model;
}

// The timed motion: the grasper sways +-0.5 mm about 2 mm below its grasp (period 100 steps).
constexpr double kGrasperHold = kGallbladderBottomInsertion - 0.001 - 0.002;
constexpr int kSwaySteps = 100;

std::array<InstrumentPose, 2> TimedPoses(const DissectionModel& model, bool hook_on_liver, long step) {
  std::array<InstrumentPose, 2> p{};
  p[0].insertion_m = kGrasperHold + 0.0005 * std::sin(2 * std::numbers::pi * static_cast<double>(step) / kSwaySteps);
  p[0].jaw_angle_rad = 0.0;
  if (hook_on_liver) {
    const InstrumentMount& hook = model.instruments[1];
    const Eigen::Vector3d target(0.03, 0.0, 0.004);  // on the bed face, clear of the gallbladder
    p[1] = AimAt(hook.p_RemoteCentre_W, target, (target - hook.p_RemoteCentre_W).norm() + 0.001,
                 hook.reference_direction_W);
  } else {
    p[1].insertion_m = kGallbladderBottomInsertion + 0.001;
  }
  return p;
}

bool BothToolsInContact(const DissectionScene& scene) {
  return scene.grasp().state() == GraspStateMachine::State::kHolding && scene.haptic_frame(0).active &&
         scene.haptic_frame(1).active;
}

struct SceneRun {
  std::unique_ptr<DissectionScene> scene;
  long timed_steps = 0;  // steps into the sway
};

// Grasp the bottom face (as the scene tests' GraspBottom), then over 0.3 s pull 2 mm down while
// the hook comes up to its contact, then one sway period: both tools in contact from then on.
SceneRun& WarmScene(int gallbladder_nodes, int solver, bool hook_on_liver) {
  static std::map<std::tuple<int, int, bool>, SceneRun> runs;
  SceneRun& run = runs[{gallbladder_nodes, solver, hook_on_liver}];
  if (run.scene) return run;
  run.scene = std::make_unique<DissectionScene>(CachedModel(gallbladder_nodes, solver));
  DissectionScene& scene = *run.scene;
  const DissectionModel& model = scene.model();
  const std::array<InstrumentPose, 2> target = TimedPoses(model, hook_on_liver, 0);
  const double hook_reach = target[1].insertion_m;
  std::array<InstrumentPose, 2> p = target;
  p[0].jaw_angle_rad = 0.5;
  p[1].insertion_m = 0.02;  // hook far below
  for (int k = 0; k < 40; ++k) {
    p[0].insertion_m = kGallbladderBottomInsertion - 0.001 - 0.02 * (1.0 - k / 39.0);
    scene.Step(p);
  }
  p[0].jaw_angle_rad = 0.0;
  scene.Step(p);
  if (scene.grasp().state() != GraspStateMachine::State::kHolding)
    throw std::runtime_error("scene bench: the grasper did not take hold");
  for (int k = 1; k <= 60; ++k) {
    const double a = k / 60.0;
    p[0].insertion_m = kGallbladderBottomInsertion - 0.001 - 0.002 * a;
    p[1].insertion_m = hook_reach - 0.006 * (1.0 - a);
    scene.Step(p);
  }
  for (; run.timed_steps < kSwaySteps; ++run.timed_steps) scene.Step(TimedPoses(model, hook_on_liver, run.timed_steps));
  if (!BothToolsInContact(scene)) throw std::runtime_error("scene bench: a tool is not in contact after warm-up");
  return run;
}

void BM_DissectionStep(benchmark::State& state) {
  const int nodes = static_cast<int>(state.range(0));
  const int solver = static_cast<int>(state.range(1));
  const bool hook_on_liver = state.range(2) != 0;
  SceneRun& run = WarmScene(nodes, solver, hook_on_liver);
  DissectionScene& scene = *run.scene;
  const DissectionModel& model = scene.model();
  StageTimes sum;
  double rows = 0, contact = 0, rejected = 0;
  for (auto _ : state) {
    const DissectionStepReport r = scene.Step(TimedPoses(model, hook_on_liver, run.timed_steps++));
    const StageTimes& t = r.times;
    sum.springs_us += t.springs_us;
    sum.gallbladder_us += t.gallbladder_us;
    sum.liver_us += t.liver_us;
    sum.collision_us += t.collision_us;
    sum.grasp_us += t.grasp_us;
    sum.constraints_us += t.constraints_us;
    sum.correction_us += t.correction_us;
    sum.total_us += t.total_us;
    rows += r.constraint_rows;
    contact += BothToolsInContact(scene) ? 1.0 : 0.0;
    rejected += r.gallbladder_accepted ? 0.0 : 1.0;
  }
  if (contact < static_cast<double>(state.iterations()))
    state.SkipWithError("a tool lost contact during the timed steps");
  auto mean = [](double v) { return benchmark::Counter(v, benchmark::Counter::kAvgIterations); };
  state.counters["springs_us"] = mean(sum.springs_us);
  state.counters["gallbladder_us"] = mean(sum.gallbladder_us);
  state.counters["liver_us"] = mean(sum.liver_us);
  state.counters["collision_us"] = mean(sum.collision_us);
  state.counters["grasp_us"] = mean(sum.grasp_us);
  state.counters["constraints_us"] = mean(sum.constraints_us);
  state.counters["correction_us"] = mean(sum.correction_us);
  state.counters["frames_us"] = mean(sum.total_us - sum.springs_us - sum.gallbladder_us - sum.liver_us -
                                     sum.collision_us - sum.grasp_us - sum.constraints_us - sum.correction_us);
  state.counters["total_us"] = mean(sum.total_us);
  state.counters["rows"] = mean(rows);
  state.counters["contact"] = mean(contact);
  state.counters["rejected"] = mean(rejected);
  state.counters["liver_nodes"] = model.liver->num_nodes();
  state.counters["liver_free"] = static_cast<double>(model.liver->layout.free_nodes.size());
  state.counters["liver_tris"] = static_cast<double>(model.liver->rest_surface.triangles.rows());
  state.counters["gb_nodes"] = model.gallbladder->num_nodes();
  state.counters["gb_tets"] = static_cast<double>(model.gallbladder->rest_mesh.tets.rows());
  state.counters["gb_tris"] = static_cast<double>(model.gallbladder_boundary.surface.triangles.rows());
  state.counters["springs"] = static_cast<double>(model.tissue.springs.size());
}
BENCHMARK(BM_DissectionStep)
    ->ArgsProduct({{kGallbladderSmallNodes, kGallbladderLargeNodes},
                   {kSolverPcg, kSolverCholmod, kSolverRotatedFactorGs},
                   {0, 1}})
    ->Unit(benchmark::kMicrosecond);

// Issue 30: the freed gallbladder lying on an organ. The 980-node box (PCG) with every spring cut
// under 9.81 m/s^2 along -y, over a 40 x 20 x 40 mm ellipsoid whose top is 5 mm below it (contact 1:
// warmed 1 s, it lies on it, its pressed nodes each a contact row and two friction rows), or with
// no obstacle and no liver contact (contact 0: falling freely, the step as it was before static
// obstacles existed: no contact rows).
void BM_FreedGallbladderResting(benchmark::State& state) {
  const bool contact = state.range(0) != 0;
  DissectionModelInputs in = SceneInputs(kGallbladderSmallNodes, kSolverPcg);
  in.settings.gravity_m_per_s2 = {0, -9.81, 0};
  in.settings.gallbladder_rests_on_liver = contact;
  if (contact)
    in.obstacles.ellipsoids.push_back(
        {"bench organ",
         {testing::kShiftX + 0.006, testing::kGallbladderBottomY - 0.025, testing::kShiftZ},
         {0.04, 0.02, 0.04}});
  DissectionScene scene(BuildDissectionModel(in));
  for (size_t k = 0; k < scene.tissue().springs.size(); ++k) scene.CutSpring(static_cast<int>(k));
  const std::array<InstrumentPose, 2> away{};
  for (int k = 0; k < 200; ++k) scene.Step(away);
  double rows = 0, contacts = 0, collision = 0, constraints = 0, sweeps = 0;
  for (auto _ : state) {
    const DissectionStepReport r = scene.Step(away);
    rows += r.constraint_rows;
    sweeps += r.constraints.iterations;
    contacts += r.obstacle_contacts;
    collision += r.times.collision_us;
    constraints += r.times.constraints_us;
  }
  auto mean = [](double v) { return benchmark::Counter(v, benchmark::Counter::kAvgIterations); };
  state.counters["rows"] = mean(rows);
  state.counters["pressed"] = mean(contacts);
  state.counters["collision_us"] = mean(collision);
  state.counters["constraints_us"] = mean(constraints);
  state.counters["sweeps"] = mean(sweeps);
}
BENCHMARK(BM_FreedGallbladderResting)->Arg(0)->Arg(1)->Iterations(400)->Unit(benchmark::kMicrosecond);

// Two consecutive hook frames of the 980-node scene (pressing the gallbladder).
std::array<HapticContactFrame, 2> HookFrames() {
  SceneRun& run = WarmScene(kGallbladderSmallNodes, kSolverPcg, false);
  std::array<HapticContactFrame, 2> frames;
  for (HapticContactFrame& f : frames) {
    run.scene->Step(TimedPoses(run.scene->model(), false, run.timed_steps++));
    f = run.scene->haptic_frame(1);
  }
  if (!frames[0].active || !frames[1].active) throw std::runtime_error("scene bench: hook frame not active");
  return frames;
}

void BM_HapticForceUpdate(benchmark::State& state) {
  const std::array<HapticContactFrame, 2> frames = HookFrames();
  const double h = 0.005, tick = 0.001;
  HapticForceRenderer renderer(h);
  // The tool keeps pressing at 10 mm/s along the frame's normal, within 0.1 mm of the solve point.
  const Eigen::Vector3d p0 = frames[0].p_Tool_W, v = -frames[0].normal_W * 0.01;
  long k = 0;
  for (auto _ : state) {
    const double t = static_cast<double>(k) * tick;
    const Eigen::Vector3d p = p0 + v * static_cast<double>(k % 10) * tick;
    if (k % 5 == 0) renderer.Update(frames[static_cast<size_t>((k / 5) % 2)], p, t);
    benchmark::DoNotOptimize(renderer.Force(p, t));
    ++k;
  }
}
BENCHMARK(BM_HapticForceUpdate)->Unit(benchmark::kNanosecond);

void BM_RenderContactForce(benchmark::State& state) {
  const HapticContactFrame frame = HookFrames()[0];
  const Eigen::Vector3d p0 = frame.p_Tool_W, step = -frame.normal_W * 1e-5;
  long k = 0;
  for (auto _ : state) {
    const Eigen::Vector3d p = p0 + step * static_cast<double>(k++ % 10);
    benchmark::DoNotOptimize(RenderContactForce(frame, p));
  }
}
BENCHMARK(BM_RenderContactForce)->Unit(benchmark::kNanosecond);

}  // namespace
}  // namespace vesica::physics
