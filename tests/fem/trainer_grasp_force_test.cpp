// Issue 37 end to end: the trainer's own scene (physics/scene/dissection_scene.h: the corotational
// gallbladder_1000 stepped by its rotated-factor PCG, the BEM liver, the grasp's constraint rows)
// grasps the gallbladder where the CalculiX reference puts the jaw and pulls it 5 mm out along
// the surface's normal, the bed held as in the reference (tests/fem/data/gallbladder_grasp_reference.txt,
// level 4, converged). The force the grasper feels must be the continuum's within 10 %: measured
// 5.4 % below it (0.1244 N against 0.1315 N), 4.4 % of which is the grasp's own give in series
// (DissectionSettings::grasp_compliance_m_per_N, 2 mm/N). Without the jaw's subgrid compliance it
// is the linear tets' stiffness: 18.8 % (29 % in linear statics, less the same give).

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <string>

#include "physics/instrument/instrument_tool.h"
#include "physics/mesh/mesh_topology.h"
#include "physics/scene/dissection_scene.h"
#include "tools/convergence/gallbladder_grasp_study.h"
#include "tools/convergence/liver_hook_study.h"

namespace vesica::convergence {
namespace {

constexpr double kShaftTilt_rad = 0.35;  // the shaft 20 degrees off the normal, toward the jaw's long side
constexpr double kRemoteCentreDistance_m = 0.08;

struct Pull {
  Eigen::Vector3d force_change_N = Eigen::Vector3d::Zero();  // after the pull less before it
  Eigen::Vector3d jaw_axis_used = Eigen::Vector3d::Zero();
  bool adopted = false;
};

enum class Load { kPull, kPress };

// subgrid false: the jaw's footprint without its subgrid compliance (a pull), or the touched
// point instead of the footprint (a press).
Pull GraspAndPull(bool subgrid, Load load = Load::kPull) {
  const std::string root = VESICA_SOURCE_DIR;
  const ToolLoadReference ref =
      load == Load::kPull ? ReadGallbladderGraspReference(root) : ReadGallbladderPressReference(root);
  physics::DissectionModelInputs in;
  in.liver_surface = ReadTrainerLiver(root);
  in.liver_source = "data/anatomy/liver.vtk";
  in.liver_material = {170e3, 0.4, 1060.0};
  in.gallbladder_mesh = ReadTrainerGallbladder(root, 1000);
  in.gallbladder_source = "data/anatomy/gallbladder_1000.vtu";
  in.gallbladder.body_name = "gallbladder_1000";
  in.gallbladder.material = {2300.0, 0.45, 1000.0};
  in.gallbladder.element_model = physics::ElementModel::kCorotational;
  in.gallbladder.solver = physics::LinearSolverKind::kRotatedFactorPcg;
  in.gallbladder.rayleigh_mass_per_s = 5.0;  // settles in a second (the trainer's 0.1 rings longer)
  in.gallbladder.rayleigh_stiffness_s = 0.01;
  // The bed as the reference holds it: the boundary nodes within 6 mm of a liver vertex.
  const physics::TetBoundary boundary = physics::ExtractBoundary(in.gallbladder_mesh);
  for (int s = 0; s < boundary.surface.num_vertices(); ++s) {
    const Eigen::RowVector3d p = boundary.surface.vertices.row(s);
    if ((in.liver_surface.vertices.rowwise() - p).rowwise().norm().minCoeff() < kBedDistance_m)
      in.gallbladder_fixed_nodes.push_back({boundary.surface_to_volume[s], {true, true, true}});
  }
  // The grasper's shaft comes at the jaw's centre 20 degrees off the normal toward the jaw's long
  // side, so the jaw lies as the reference's does; the hook waits far away.
  const Eigen::Vector3d normal = (load == Load::kPull ? 1.0 : -1.0) * ref.prescribed_m.normalized();
  const Eigen::Vector3d axis = (ref.jaw_long_axis - ref.jaw_long_axis.dot(normal) * normal).normalized();
  const Eigen::Vector3d shaft = (-std::cos(kShaftTilt_rad) * normal + std::sin(kShaftTilt_rad) * axis).normalized();
  const Eigen::Vector3d remote_centre = ref.centre_m - kRemoteCentreDistance_m * shaft;
  in.instruments[0] = {physics::InstrumentRole::kGrasper, remote_centre, shaft};
  in.instruments[1] = {physics::InstrumentRole::kCauteryHook, remote_centre + 0.05 * normal.unitOrthogonal(), shaft};
  in.settings.gallbladder_rests_on_liver = false;
  if (!subgrid && load == Load::kPull) in.settings.grasp_subgrid_adopt_steps = 1 << 30;  // never adopted
  if (!subgrid && load == Load::kPress) in.settings.grasper_presses_jaw_footprint = false;
  auto model = physics::BuildDissectionModel(in);
  physics::DissectionScene scene(model);

  std::array<physics::InstrumentPose, 2> p{};
  p[1].insertion_m = 0.01;
  auto aim = [&](const Eigen::Vector3d& tip, double jaw) {
    p[0] = physics::AimAt(remote_centre, tip, (tip - remote_centre).norm(), shaft);
    p[0].jaw_angle_rad = jaw;
  };
  // Approach with the jaw open to the surface and close on it (pull), or closed to the surface
  // (press: the closed jaws' side pushes the wall).
  const double jaw = load == Load::kPull ? 0.5 : 0.0;
  for (int k = 0; k <= 40; ++k) {
    aim(ref.centre_m - 0.02 * (1.0 - k / 40.0) * shaft, jaw);
    scene.Step(p);
  }
  aim(ref.centre_m, 0.0);
  for (int k = 0; k < 200; ++k) scene.Step(p);  // the subgrid adopted at 60, ramped by 80; settled
  if (load == Load::kPull) {
    EXPECT_EQ(scene.grasp().state(), physics::GraspStateMachine::State::kHolding);
  }
  const Eigen::Vector3d before = scene.Step(p).tool_force_N[0];
  // Pull 5 mm out along the normal over 1 s, hold 2 s.
  physics::DissectionStepReport r;
  for (int k = 1; k <= 600; ++k) {
    aim(ref.centre_m + std::min(1.0, k / 200.0) * ref.prescribed_m, 0.0);
    r = scene.Step(p);
    EXPECT_TRUE(r.gallbladder_accepted) << r.rejection_reason;
  }
  if (load == Load::kPull) {
    EXPECT_EQ(scene.grasp().state(), physics::GraspStateMachine::State::kHolding);
  }
  Pull out;
  // The tool feels the tissue pull back: the reaction on the jaw is the force the reference
  // reports on the footprint, with the opposite sign.
  out.force_change_N = -(r.tool_force_N[0] - before);
  out.adopted = scene.grasp_jaw().computed().has_value();
  return out;
}

TEST(TrainerGraspForceTest, TheScenesGraspPullIsTheContinuumsWithinTenPercent) {
  const ToolLoadReference ref = ReadGallbladderGraspReference(VESICA_SOURCE_DIR);
  const Pull with = GraspAndPull(true);
  const Pull without = GraspAndPull(false);
  ASSERT_TRUE(with.adopted);
  EXPECT_FALSE(without.adopted);
  const double error_with = (with.force_change_N - ref.force_N).norm() / ref.force_N.norm();
  const double error_without = (without.force_change_N - ref.force_N).norm() / ref.force_N.norm();
  std::printf("reference %.5f N (%.5f %.5f %.5f)\n", ref.force_N.norm(), ref.force_N.x(), ref.force_N.y(),
              ref.force_N.z());
  std::printf("scene, jaw footprint + subgrid: %.5f N (%.5f %.5f %.5f), error %.1f %%\n", with.force_change_N.norm(),
              with.force_change_N.x(), with.force_change_N.y(), with.force_change_N.z(), 100 * error_with);
  std::printf("scene, jaw footprint alone:     %.5f N, error %.1f %%\n", without.force_change_N.norm(),
              100 * error_without);
  EXPECT_LT(error_with, 0.10);
  EXPECT_GT(error_without, 0.15);  // the linear tets' stiffness, which the subgrid compliance removes
}

// The closed jaws pressed 5 mm into the wall, frictionless (the press reference): the jaw's
// footprint with its press subgrid compliance (per surface vertex, computed on a worker) against the
// touched point alone. The force's direction is the touched triangle's current normal, which the
// 5 mm dent and the mesh's facets tilt from the reference's (linear statics, the rest normal): held
// to 15 degrees.
TEST(TrainerGraspForceTest, TheScenesClosedJawsPressIsTheContinuumsWithinTenPercent) {
  const ToolLoadReference ref = ReadGallbladderPressReference(VESICA_SOURCE_DIR);
  const Pull with = GraspAndPull(true, Load::kPress);
  const Pull point = GraspAndPull(false, Load::kPress);
  const double ref_n = ref.force_N.norm();
  const double angle = std::acos(with.force_change_N.normalized().dot(ref.force_N.normalized()));
  std::printf(
      "press reference %.5f N; scene, jaw footprint + subgrid %.5f N (%.1f %%, %.1f degrees off); "
      "the touched point %.5f N (%.1f %%)\n",
      ref_n, with.force_change_N.norm(), 100 * (with.force_change_N.norm() / ref_n - 1), angle * 180 / M_PI,
      point.force_change_N.norm(), 100 * (point.force_change_N.norm() / ref_n - 1));
  EXPECT_NEAR(with.force_change_N.norm(), ref_n, 0.10 * ref_n);
  EXPECT_LT(angle, 15.0 * M_PI / 180);
  EXPECT_LT(point.force_change_N.norm(), 0.7 * ref_n);  // a point on the coarse mesh gives far too easily
}

}  // namespace
}  // namespace vesica::convergence
