// Registration frame rate at the seed's size (issue 35): the liver surface meshed to 1,294 nodes,
// 30 control points (18 near the coronal plane, 12 near the sagittal one) following a breathing
// translation. One "frame" is one registration step (free FE step, pairing, W, solve,
// correction), as the seed's 76 FPS counts. Stages are timed apart to show what bounds it.

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "app/anatomy/tet_mesher.h"
#include "app/mesh_io/mesh_io.h"
#include "physics/mesh/mesh_topology.h"
#include "physics/registration/registration_fem_settings.h"
#include "physics/registration/registration_solver.h"

namespace {

using namespace vesica::physics;

struct Scene {
  std::shared_ptr<const FemModel> model;
  std::vector<ControlPoint> rest_points;
};

// Surface vertices nearest each plane, spread by angle about the plane's centre.
void PickPlanePoints(const TetBoundary& b, const Vertices& x, const Eigen::Vector3d& centre, int axis, int count,
                     std::vector<ControlPoint>& out) {
  const int u = axis == 0 ? 1 : 0, v = axis == 2 ? 1 : 2;
  std::vector<int> best(static_cast<size_t>(count), -1);
  std::vector<double> best_score(static_cast<size_t>(count), 1e9);
  Vertices normals = Vertices::Zero(b.surface.num_vertices(), 3);
  for (int f = 0; f < b.surface.num_triangles(); ++f) {
    const Eigen::Vector3d n = TriangleNormal(b.surface, f);
    for (int k = 0; k < 3; ++k) normals.row(b.surface.triangles(f, k)) += n.transpose();
  }
  for (int s = 0; s < b.surface.num_vertices(); ++s) {
    const Eigen::Vector3d p = x.row(b.surface_to_volume[s]).transpose();
    if (std::abs(p[axis] - centre[axis]) > 0.006) continue;
    const double angle = std::atan2(p[v] - centre[v], p[u] - centre[u]) + std::numbers::pi;
    const int slot = std::min(count - 1, static_cast<int>(angle / (2 * std::numbers::pi) * count));
    const double score = std::abs(p[axis] - centre[axis]);
    if (score < best_score[static_cast<size_t>(slot)]) {
      best_score[static_cast<size_t>(slot)] = score;
      best[static_cast<size_t>(slot)] = s;
    }
  }
  for (int s : best)
    if (s >= 0)
      out.push_back({x.row(b.surface_to_volume[s]).transpose(), -normals.row(s).normalized().transpose(), 1.0, axis});
}

const Scene& GetScene() {
  static const Scene scene = [] {
    const TriangleMesh surface = vesica::app::ReadTriangleMesh(
        std::string(VESICA_SOURCE_DIR) + "/data/anatomy/liver.vtk", SurfaceRequirement::kClosed);
    // 1,294 nodes and 4,808 tets (tests/registration/registration_liver.h).
    const TetrahedralMesh mesh = vesica::app::anatomy::Tetrahedralise(surface, "pq2/5a1.1214e-06O2/7YQ");
    Scene s;
    s.model = std::make_shared<const FemModel>(BuildFemModel(mesh, DefaultRegistrationFemSettings("liver"), {}));
    const TetBoundary boundary = ExtractBoundary(mesh);
    const Eigen::Vector3d centre = mesh.vertices.colwise().mean().transpose();
    PickPlanePoints(boundary, mesh.vertices, centre, 1, 18, s.rest_points);
    PickPlanePoints(boundary, mesh.vertices, centre, 0, 12, s.rest_points);
    return s;
  }();
  return scene;
}

// The points of frame k of a 4 s breath sampled every 0.4175 s (the seed's): 20 mm caudal, 8 mm
// anterior at full inspiration.
std::vector<ControlPoint> FramePoints(const Scene& s, int frame) {
  const double phase = std::pow(std::sin(std::numbers::pi * frame * 0.4175 / 4.0), 2);
  std::vector<ControlPoint> points = s.rest_points;
  for (ControlPoint& p : points) p.p_W += phase * Eigen::Vector3d(0.002, 0.008, -0.020);
  return points;
}

void BM_RegistrationFrame(benchmark::State& state) {
  const Scene& s = GetScene();
  RegistrationSolver solver(s.model, {});
  std::vector<std::vector<ControlPoint>> frames;
  for (int f = 0; f < 46; ++f) frames.push_back(FramePoints(s, f));
  for (int warm = 0; warm < 46 * 4; ++warm)
    solver.Step(frames[static_cast<size_t>(warm / 4)]);  // caches every node's C0 columns it meets
  long long step = 0;
  double fem_iterations = 0, constraint_iterations = 0;
  for (auto _ : state) {
    // Four steps per image frame, frames cycling: the points move every fourth step.
    const RegistrationStepReport r = solver.Step(frames[static_cast<size_t>((step / 4) % 46)]);
    fem_iterations += r.fem.solver_iterations;
    constraint_iterations += r.constraints.iterations;
    ++step;
  }
  state.counters["FPS"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["nodes"] = s.model->num_nodes();
  state.counters["tets"] = s.model->rest_mesh.num_tets();
  state.counters["points"] = static_cast<double>(s.rest_points.size());
  state.counters["pcg_iterations"] = fem_iterations / static_cast<double>(step);
  state.counters["gauss_seidel_sweeps"] = constraint_iterations / static_cast<double>(step);
}
// Rates per CPU second (the machine is shared; one thread does the work): FPS on one core.
BENCHMARK(BM_RegistrationFrame)->Unit(benchmark::kMillisecond);

// The free step alone (FemBody::Step of the same body, no constraints): the FE share of a frame.
void BM_FreeFemStep(benchmark::State& state) {
  const Scene& s = GetScene();
  FemBody body(s.model);
  Eigen::VectorXd u = Eigen::VectorXd::Zero(s.model->num_dofs());
  for (int i = 0; i < s.model->num_nodes(); ++i)
    u[3 * i + 2] = 0.02 * std::pow(s.model->rest_mesh.vertices(i, 0) / 0.1, 2);
  for (auto _ : state) {
    body.SetState(u, Eigen::VectorXd::Zero(u.size()));  // deformed: the step has work to do
    benchmark::DoNotOptimize(body.Step());
  }
}
BENCHMARK(BM_FreeFemStep)->Unit(benchmark::kMillisecond);

// Pairing alone: 30 points against the surface, normal-checked.
void BM_Pairing(benchmark::State& state) {
  const Scene& s = GetScene();
  const RegistrationSurface surface(ExtractBoundary(s.model->rest_mesh));
  const std::vector<ControlPoint> points = FramePoints(s, 5);
  for (auto _ : state) {
    const SurfaceSnapshot snapshot(surface, s.model->rest_mesh.vertices);
    for (const ControlPoint& p : points) benchmark::DoNotOptimize(PairControlPoint(snapshot, p, {}));
  }
}
BENCHMARK(BM_Pairing)->Unit(benchmark::kMicrosecond);

}  // namespace
