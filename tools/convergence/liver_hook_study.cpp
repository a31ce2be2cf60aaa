#include "tools/convergence/liver_hook_study.h"

#include <Eigen/Geometry>
#include <Eigen/QR>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <set>
#include <vector>

#include "app/mesh_io/mesh_io.h"
#include "physics/bem/capacitance_solver.h"
#include "physics/bem/footprint_contact_solver.h"
#include "physics/bem/graded_surface_refinement.h"
#include "physics/bem/tool_contact_load.h"

namespace vesica::convergence {
namespace {

using physics::TriangleMesh;

// The hook's tip: the footprint vertex shared by every footprint triangle.
int TipVertex(const TriangleMesh& surface, const std::vector<int>& contact) {
  const std::set<int> in(contact.begin(), contact.end());
  std::vector<int> count(static_cast<std::size_t>(surface.num_vertices()), 0);
  for (int f = 0; f < surface.num_triangles(); ++f) {
    bool all = true;
    for (int c = 0; c < 3; ++c) all = all && in.count(surface.triangles(f, c)) > 0;
    if (all)
      for (int c = 0; c < 3; ++c) ++count[static_cast<std::size_t>(surface.triangles(f, c))];
  }
  return static_cast<int>(std::max_element(count.begin(), count.end()) - count.begin());
}

}  // namespace

LiverHookSetup MakeLiverHookSetup(const TriangleMesh& trainer, const ToolLoadReference& ref, int levels,
                                  LiverGrading grading) {
  const int tip = TipVertex(trainer, ref.contact);
  std::set<int> ring_triangles;
  for (int f = 0; f < trainer.num_triangles(); ++f)
    for (int c = 0; c < 3; ++c)
      if (trainer.triangles(f, c) == tip) ring_triangles.insert(f);
  double footprint_m = 0;
  for (int v : ref.contact)
    footprint_m = std::max(footprint_m, (trainer.vertices.row(v) - trainer.vertices.row(tip)).norm());
  std::vector<double> radii;
  physics::Vertices centres = trainer.vertices.row(tip);
  if (grading == LiverGrading::kTowardTip) {
    for (int l = 0; l < levels; ++l) radii.push_back(4.0 * footprint_m * std::pow(0.6, l));
  } else {
    std::vector<int> bed;
    for (int v = 0; v < trainer.num_vertices(); ++v)
      if (trainer.vertex_labels(v) & physics::kLabelGallbladderBed) bed.push_back(v);
    centres.resize(static_cast<Eigen::Index>(bed.size()), 3);
    for (std::size_t k = 0; k < bed.size(); ++k)
      centres.row(static_cast<Eigen::Index>(k)) = trainer.vertices.row(bed[k]);
    for (int l = 0; l < levels; ++l) radii.push_back(0.5 * footprint_m * std::pow(0.6, l));
  }
  physics::RefinedSurface refined = physics::RefineTowardPoints(trainer, centres, radii);

  LiverHookSetup setup;
  std::set<int> contact;
  double edge_sum = 0;
  int edges = 0;
  for (int f = 0; f < refined.surface.num_triangles(); ++f) {
    if (!ring_triangles.count(refined.parent_triangle(f))) continue;
    setup.footprint_triangles.push_back(f);
    setup.footprint_parents.push_back(refined.parent_triangle(f));
    for (int c = 0; c < 3; ++c) {
      const int a = refined.surface.triangles(f, c), b = refined.surface.triangles(f, (c + 1) % 3);
      contact.insert(a);
      edge_sum += (refined.surface.vertices.row(a) - refined.surface.vertices.row(b)).norm();
      ++edges;
    }
  }
  setup.tip = tip;
  setup.footprint_radius_m = footprint_m;
  setup.surface = std::move(refined.surface);
  setup.contact.assign(contact.begin(), contact.end());
  setup.contact_edge_m = edge_sum / edges;
  return setup;
}

LiverHookResult SolveLiverHook(const TriangleMesh& trainer, const ToolLoadReference& ref, const LiverHookSetup& setup) {
  const auto start = std::chrono::steady_clock::now();
  const physics::BemModel model = physics::PrecomputeBemModel(setup.surface, physics::LiverMaterial(), "study liver");
  const double precompute_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  LiverHookResult r = SolveLiverHook(trainer, ref, setup, model);
  r.precompute_s = precompute_s;
  return r;
}

LiverHookResult SolveLiverHook(const TriangleMesh& trainer, const ToolLoadReference& ref, const LiverHookSetup& setup,
                               const physics::BemModel& model) {
  LiverHookResult r;
  physics::BemCapacitanceSolver solver(model);
  solver.SetContactNodes(setup.contact);
  const physics::Vertices prescribed =
      ref.prescribed_m.transpose().replicate(static_cast<Eigen::Index>(setup.contact.size()), 1);
  physics::Vertices forces_N;
  solver.ContactForces(prescribed, forces_N);
  physics::BemSolution solution;
  solver.Solve(prescribed, solution);

  r.vertices = setup.surface.num_vertices();
  r.contact_edge_m = setup.contact_edge_m;
  r.force_N = forces_N.colwise().sum().transpose();
  r.force_error = (r.force_N - ref.force_N).norm() / ref.force_N.norm();
  for (int f : setup.footprint_triangles)
    for (int c = 0; c < 3; ++c)
      r.footprint_force_N += solution.traction_Pa.row(setup.surface.triangles(f, c)).transpose() *
                             physics::TriangleArea(setup.surface, f) / 3.0;
  r.footprint_force_error = (r.footprint_force_N - ref.force_N).norm() / ref.force_N.norm();
  const std::set<int> contact(setup.contact.begin(), setup.contact.end());
  double diff2 = 0, ref2 = 0;
  for (int v = 0; v < trainer.num_vertices(); ++v) {
    if (contact.count(v) || (trainer.vertex_labels(v) & physics::kLabelFixed)) continue;
    diff2 += (solution.displacement_m.row(v) - ref.displacement_m.row(v)).squaredNorm();
    ref2 += ref.displacement_m.row(v).squaredNorm();
  }
  r.displacement_error = std::sqrt(diff2 / ref2);
  return r;
}

physics::ToolFootprint OneRingFootprint(const TriangleMesh& trainer, const LiverHookSetup& setup) {
  physics::ToolFootprint footprint;
  footprint.triangles = setup.footprint_triangles;
  footprint.centre_W = trainer.vertices.row(setup.tip).transpose();
  footprint.radius_m = setup.footprint_radius_m;
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  std::map<int, Eigen::Matrix3d> ring;  // refined triangle -> columns tip, a, b of its parent
  for (std::size_t k = 0; k < setup.footprint_triangles.size(); ++k) {
    const int parent = setup.footprint_parents[k];
    int c = 0;
    while (trainer.triangles(parent, c) != setup.tip) ++c;
    Eigen::Matrix3d corners;
    for (int j = 0; j < 3; ++j)
      corners.col(j) = trainer.vertices.row(trainer.triangles(parent, (c + j) % 3)).transpose();
    normal += (corners.col(1) - corners.col(0)).cross(corners.col(2) - corners.col(0));
    ring[setup.footprint_triangles[k]] = corners;
  }
  footprint.normal_W = normal.normalized();
  footprint.rho = [ring = std::move(ring)](int f, const Eigen::Vector3d& p) {
    const Eigen::Matrix3d& x = ring.at(f);
    Eigen::Matrix<double, 3, 2> edges;
    edges << x.col(1) - x.col(0), x.col(2) - x.col(0);
    const Eigen::Vector2d st = edges.colPivHouseholderQr().solve(p - x.col(0));
    return st.sum();  // 1 - the tip's barycentric coordinate
  };
  return footprint;
}

LiverHookResult SolveLiverHookWithModes(const TriangleMesh& trainer, const ToolLoadReference& ref,
                                        const LiverHookSetup& setup, const physics::BemModel& model,
                                        const physics::FootprintOptions& options) {
  const physics::FootprintModes modes =
      physics::MakeFootprintModes(setup.surface, model.lumped_area_m2, OneRingFootprint(trainer, setup), options);
  physics::BemFootprintSolver solver(model);
  solver.SetFootprint(modes);
  LiverHookResult r;
  r.vertices = setup.surface.num_vertices();
  r.contact_edge_m = setup.contact_edge_m;
  r.force_N = solver.ContactForce(ref.prescribed_m);
  r.force_error = (r.force_N - ref.force_N).norm() / ref.force_N.norm();
  r.footprint_force_N = r.force_N;
  r.footprint_force_error = r.force_error;
  physics::BemSolution solution;
  solver.Solve(ref.prescribed_m, solution);
  const std::set<int> contact(ref.contact.begin(), ref.contact.end());
  double diff2 = 0, ref2 = 0;
  for (int v = 0; v < trainer.num_vertices(); ++v) {
    if (contact.count(v) || (trainer.vertex_labels(v) & physics::kLabelFixed)) continue;
    diff2 += (solution.displacement_m.row(v) - ref.displacement_m.row(v)).squaredNorm();
    ref2 += ref.displacement_m.row(v).squaredNorm();
  }
  r.displacement_error = std::sqrt(diff2 / ref2);
  return r;
}

double LiverDiscPushForce(const TriangleMesh& trainer, const ToolLoadReference& ref, const LiverHookSetup& setup,
                          const physics::BemModel& model, double radius_m) {
  const physics::ToolFootprint ring = OneRingFootprint(trainer, setup);
  const Eigen::Vector3d normal = ring.normal_W;
  // The tip vertex is a corner of its first ring triangle on every level (old vertices keep
  // their indices): barycentric weights 1 there.
  int triangle = -1;
  Eigen::Vector3d weights = Eigen::Vector3d::Zero();
  for (int f : setup.footprint_triangles)
    for (int c = 0; c < 3 && triangle < 0; ++c)
      if (setup.surface.triangles(f, c) == setup.tip) triangle = f, weights[c] = 1.0;
  const physics::BemContactLoad load = physics::MakeToolContactLoad(model, triangle, weights, normal, radius_m);
  const double compliance_m_per_N = normal.dot(physics::ContactLoadCompliance(model, load, load) * normal);
  return std::abs(normal.dot(ref.prescribed_m)) / compliance_m_per_N;
}

TriangleMesh ReadTrainerLiver(const std::string& source_dir) {
  return app::ReadTriangleMesh(source_dir + "/data/anatomy/liver.vtk", physics::SurfaceRequirement::kClosed);
}

ToolLoadReference ReadLiverHookReference(const std::string& source_dir) {
  return ReadToolLoadReference(source_dir + "/tests/bem/data/liver_hook_reference.txt");
}

}  // namespace vesica::convergence
