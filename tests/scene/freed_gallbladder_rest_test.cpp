// Issue 30: a freed gallbladder released in the abdomen rests on what lies below it, not in
// mid-air and not through the liver. The surgeon's-view model is built as the app builds it
// (app/session/dissection_setup.cpp: the solid [[context_organs]] become static obstacles); every
// spring is cut, the resident's instruments are out (at their trocars), the assistant still holds
// the fundus (as in the operation until the gallbladder is bagged), and the scene runs for 5 s
// under the scenario's gravity (2 m/s^2, reverse Trendelenburg and left tilt).
// Depths are measured independently of the scene's contact code: inside the liver by brute force
// over all its triangles, inside an organ by its closed form (tube) or implicit function (ellipsoid).

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cstdio>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>

#include "app/render/scene_meshes.h"
#include "app/scenario/scenario_loader.h"
#include "app/session/dissection_setup.h"
#include "physics/bem/dense_lu_solve.h"
#include "physics/collision/ellipsoid_distance.h"
#include "physics/mesh/barycentric.h"
#include "physics/scene/dissection_scene.h"

namespace vesica::app {
namespace {

namespace fs = std::filesystem;

struct Released {
  double max_speed_m_per_s = 0;  // fastest gallbladder node at the end
  double liver_depth_m = 0;      // deepest a surface node got inside the liver (sampled every 0.1 s)
  double organ_depth_m = 0;      // deepest inside a solid organ (same samples)
  double nearest_support_m = 0;  // at the end: the surface node nearest the liver or a solid organ, how far
  int pressed_nodes = 0;         // nodes the liver or an organ pushed in the last step
};

// Signed distance to the liver by brute force over all its triangles; the sign from the nearest
// triangle's outward normal.
double LiverSignedDistance(const physics::TriangleMesh& liver, const physics::Vertices& x, const Eigen::Vector3d& p) {
  double best = std::numeric_limits<double>::infinity(), sign = 1;
  for (int f = 0; f < liver.num_triangles(); ++f) {
    const Eigen::Vector3d a = x.row(liver.triangles(f, 0)).transpose(), b = x.row(liver.triangles(f, 1)).transpose(),
                          c = x.row(liver.triangles(f, 2)).transpose();
    const physics::TrianglePoint cp = physics::ClosestPointOnTriangle(p, a, b, c);
    const double d = (p - cp.point).norm();
    if (d < best - 1e-12) {
      best = d;
      sign = (b - a).cross(c - a).dot(p - cp.point) >= 0 ? 1 : -1;
    }
  }
  return sign * best;
}

// Depth inside a solid organ (> 0 inside), 0 outside: a tube's closed form; for an ellipsoid the
// implicit function's radial estimate (exact on a sphere, a bound to first order otherwise).
double OrganDepth(const ContextOrgan& o, const Eigen::Vector3d& p) {
  if (o.shape == ContextOrgan::Shape::kTube)
    return std::max(0.0, -physics::TubeProximity({o.name, o.points_m, o.radius_m}, p).signed_distance_m);
  const Eigen::Vector3d q = (p - o.centre_m).cwiseQuotient(o.semi_axes_m);
  const double r = q.norm();
  return r < 1.0 ? (1.0 - r) * o.semi_axes_m.minCoeff() : 0.0;
}

Released Release(bool with_contact, double seconds) {
  physics::ScopedDenseLinearAlgebraThreads one_thread{1};  // as the session runs it
  const Scenario scenario =
      LoadScenario(fs::path(VESICA_SOURCE_DIR) / "data/scenarios/cholecystectomy.toml");
  const SceneMeshes meshes = LoadSceneMeshes(scenario);
  physics::DissectionModelInputs in = MakeDissectionInputs(scenario, meshes);
  if (!with_contact) {
    in.obstacles = {};
    in.settings.gallbladder_rests_on_liver = false;
  }
  const auto model = physics::BuildDissectionModel(in);
  physics::DissectionScene scene(model);
  for (size_t s = 0; s < scene.tissue().springs.size(); ++s) scene.CutSpring(static_cast<int>(s));
  const std::array<physics::InstrumentPose, 2> away{};  // insertion 0: the tips at the trocars
  const Eigen::VectorXi& surface = model->gallbladder_boundary.surface_to_volume;
  const int steps = static_cast<int>(seconds / model->settings.time_step_s);
  Released out;
  for (int k = 1; k <= steps; ++k) {
    out.pressed_nodes = scene.Step(away).obstacle_contacts;
    if (k % 20 != 0) continue;
    const physics::Vertices x = scene.gallbladder().CurrentPositions();
    if (k % 100 == 0) {
      double fastest = 0;
      const Eigen::VectorXd& v = scene.gallbladder().state().velocity_m_per_s;
      for (Eigen::Index n = 0; n < v.size() / 3; ++n) fastest = std::max(fastest, v.segment<3>(3 * n).norm());
      std::printf("  %.1f s: fastest node %.3f mm/s, %d nodes pressed\n", scene.time_s(), 1e3 * fastest,
                  out.pressed_nodes);
    }
    for (Eigen::Index b = 0; b < surface.size(); ++b) {
      const Eigen::Vector3d p = x.row(surface[b]).transpose();
      out.liver_depth_m =
          std::max(out.liver_depth_m, -LiverSignedDistance(model->liver->rest_surface, scene.liver_positions(), p));
      for (const ContextOrgan& o : scenario.context_organs)
        if (o.solid) out.organ_depth_m = std::max(out.organ_depth_m, OrganDepth(o, p));
    }
  }
  const physics::Vertices x = scene.gallbladder().CurrentPositions();
  const Eigen::VectorXd& v = scene.gallbladder().state().velocity_m_per_s;
  for (Eigen::Index n = 0; n < v.size() / 3; ++n)
    out.max_speed_m_per_s = std::max(out.max_speed_m_per_s, v.segment<3>(3 * n).norm());
  out.nearest_support_m = std::numeric_limits<double>::infinity();
  for (Eigen::Index b = 0; b < surface.size(); ++b) {
    const Eigen::Vector3d p = x.row(surface[b]).transpose();
    double d = std::abs(LiverSignedDistance(model->liver->rest_surface, scene.liver_positions(), p));
    for (const ContextOrgan& o : scenario.context_organs) {
      if (!o.solid) continue;
      d = std::min(d, std::abs(o.shape == ContextOrgan::Shape::kTube
                                   ? physics::TubeProximity({o.name, o.points_m, o.radius_m}, p).signed_distance_m
                                   : physics::ClosestPointOnEllipsoid(o.centre_m, o.semi_axes_m, p).signed_distance_m));
    }
    out.nearest_support_m = std::min(out.nearest_support_m, d);
  }
  std::printf(
      "surgeon's view, contact %s, %.1f s after the last spring: fastest node %.3f mm/s; deepest in the liver "
      "%.2f mm, in an organ %.2f mm; nearest node to a support %.3f mm; %d nodes pressed\n",
      with_contact ? "on" : "off", seconds, 1e3 * out.max_speed_m_per_s, 1e3 * out.liver_depth_m,
      1e3 * out.organ_depth_m, 1e3 * out.nearest_support_m, out.pressed_nodes);
  return out;
}

TEST(FreedGallbladderRest, SurgeonViewComesToRestOnTheLiverNotThroughIt) {
  const Released r = Release(true, 5.0);
  EXPECT_LT(r.max_speed_m_per_s, 1e-3);    // at rest: every node under 1 mm/s
  EXPECT_LT(r.liver_depth_m, 0.5e-3);      // never more than 0.5 mm into the liver
  EXPECT_LT(r.organ_depth_m, 0.5e-3);      // nor into a solid organ
  EXPECT_LT(r.nearest_support_m, 0.2e-3);  // lying on it, not in mid-air
  EXPECT_GT(r.pressed_nodes, 0);
}

TEST(FreedGallbladderRest, SurgeonViewWithoutContactSinksIntoTheLiver) {
  const Released r = Release(false, 3.0);
  EXPECT_GT(r.liver_depth_m, 1e-3);  // measured 2.4 mm by 3 s, still sinking (with contact: 0)
}

}  // namespace
}  // namespace vesica::app

namespace vesica::app {
namespace {

// The scenario key that marks which context organs hold the gallbladder up, and its defaults.
Scenario WithOrgans(const std::string& organs) {
  const fs::path path = fs::path(VESICA_SOURCE_DIR) / "data/scenarios/cholecystectomy.toml";
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf() << "\n" << organs;
  return ParseScenario(text.str(), path, path.parent_path());
}

TEST(ContextOrganSolidKey, DefaultsBulkyOrgansSolidAndThinTubesNot) {
  const Scenario s = WithOrgans(R"(
[[context_organs]]
name = "small bowel"
shape = "tube"
points_m = [[0, 0, 0], [0.05, 0, 0]]
radius_m = 0.012
rgb = [0.8, 0.5, 0.5]
[[context_organs]]
name = "right hepatic artery"
shape = "tube"
points_m = [[0, 0, 0], [0.05, 0, 0]]
radius_m = 0.002
rgb = [0.7, 0.1, 0.1]
[[context_organs]]
name = "fat pad"
shape = "ellipsoid"
centre_m = [0, 0, 0]
semi_axes_m = [0.01, 0.01, 0.01]
rgb = [0.9, 0.8, 0.4]
solid = false
)");
  const auto find = [&](const std::string& name) {
    for (const ContextOrgan& o : s.context_organs)
      if (o.name == name) return o;
    throw std::runtime_error("no organ " + name);
  };
  EXPECT_TRUE(find("small bowel").solid);
  EXPECT_FALSE(find("right hepatic artery").solid);
  EXPECT_FALSE(find("fat pad").solid);
  // The app's model gets exactly the solid ones.
  const physics::DissectionModelInputs in = MakeDissectionInputs(s, SceneMeshes{});
  size_t solid = 0;
  for (const ContextOrgan& o : s.context_organs) solid += o.solid ? 1 : 0;
  EXPECT_EQ(in.obstacles.tubes.size() + in.obstacles.ellipsoids.size(), solid);
}

TEST(ContextOrganSolidKey, ANonBooleanIsRefusedWithItsLine) {
  try {
    WithOrgans(
        "[[context_organs]]\nname = \"colon\"\nshape = \"tube\"\npoints_m = [[0, 0, 0], [0.05, 0, 0]]\n"
        "radius_m = 0.02\nrgb = [0.8, 0.5, 0.5]\nsolid = \"yes\"\n");
    FAIL() << "solid = \"yes\" was accepted";
  } catch (const std::exception& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("solid"), std::string::npos) << what;
    EXPECT_NE(what.find("must be true or false"), std::string::npos) << what;
    EXPECT_NE(what.find("cholecystectomy.toml:"), std::string::npos) << what;
  }
}

}  // namespace
}  // namespace vesica::app
