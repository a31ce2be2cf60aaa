#include "app/session/dissection_setup.h"

#include <spdlog/spdlog.h>

#include <cstdlib>
#include <functional>
#include <mutex>
#include <numbers>
#include <set>
#include <stdexcept>
#include <string>

#include "app/render/scope_pose.h"

namespace vesica::app {

namespace {
const InstrumentConfig* FindKind(const Scenario& s, InstrumentKind kind) {
  for (const InstrumentConfig& c : s.instruments)
    if (c.kind == kind) return &c;
  return nullptr;
}

physics::InstrumentMount MountOf(const Scenario& s, const InstrumentConfig& c, physics::InstrumentRole role) {
  const Eigen::Vector3d centre = s.trocar(c.trocar).position_m;
  const Eigen::Vector3d reference = s.laparoscope.look_at_m - centre;
  if (!(reference.norm() > 0))
    throw std::invalid_argument(s.source.string() + ": instrument '" + c.name +
                                "': its trocar sits on the laparoscope's target, so no shaft direction");
  return {role, centre, reference.normalized()};
}
}  // namespace

physics::DissectionModelInputs MakeDissectionInputs(const Scenario& scenario, const SceneMeshes& meshes) {
  const InstrumentConfig* grasper = FindKind(scenario, InstrumentKind::kGrasper);
  const InstrumentConfig* hook = FindKind(scenario, InstrumentKind::kCauteryHook);
  if (grasper == nullptr || hook == nullptr)
    throw std::invalid_argument(scenario.source.string() +
                                ": the dissection needs one grasper and one cautery_hook instrument");
  physics::DissectionModelInputs in;
  in.liver_surface = meshes.liver;
  in.liver_source = scenario.liver.surface_mesh.string();
  in.liver_material = {scenario.liver.material.youngs_modulus_Pa, scenario.liver.material.poisson_ratio,
                       scenario.liver.material.density_kg_per_m3};
  in.gallbladder_mesh = meshes.gallbladder;
  in.gallbladder_source = scenario.gallbladder.volume_mesh.string();
  physics::FemSettings& gb = in.gallbladder;
  gb.body_name = "gallbladder (" + scenario.gallbladder.volume_mesh.filename().string() + ")";
  gb.material = {scenario.gallbladder.material.youngs_modulus_Pa, scenario.gallbladder.material.poisson_ratio,
                 scenario.gallbladder.material.density_kg_per_m3};
  gb.element_model = scenario.gallbladder.element == FemElement::kLinear ? physics::ElementModel::kLinear
                                                                         : physics::ElementModel::kCorotational;
  switch (scenario.gallbladder.solver) {
    case FemSolver::kPcg:
      gb.solver = physics::LinearSolverKind::kPcg;
      break;
    case FemSolver::kCholmod:
      gb.solver = physics::LinearSolverKind::kCholmod;
      break;
    case FemSolver::kRotatedFactorPcg:
      gb.solver = physics::LinearSolverKind::kRotatedFactorPcg;
      gb.rotated_factor_gauss_seidel = true;  // halves the iterations on the gallbladder
      break;
  }
  gb.rayleigh_mass_per_s = scenario.gallbladder.rayleigh_mass;
  gb.rayleigh_stiffness_s = scenario.gallbladder.rayleigh_stiffness;
  in.settings.springs = {scenario.connective_tissue.stiffness_N_per_m, scenario.connective_tissue.damping_Ns_per_m};
  in.settings.attach_offset_m = scenario.connective_tissue.attach_offset_m;
  in.settings.gravity_m_per_s2 = GravityInPatientFrame(scenario.patient);  // zero without [patient]
  if (scenario.assistant_retraction) in.settings.assistant_retraction = ToPhysics(*scenario.assistant_retraction);
  for (const ContextOrgan& organ : scenario.context_organs) {  // the solid ones hold the gallbladder up
    if (!organ.solid) continue;
    if (organ.shape == ContextOrgan::Shape::kTube)
      in.obstacles.tubes.push_back({organ.name, organ.points_m, organ.radius_m});
    else
      in.obstacles.ellipsoids.push_back({organ.name, organ.centre_m, organ.semi_axes_m});
  }
  in.instruments[0] = MountOf(scenario, *grasper, physics::InstrumentRole::kGrasper);
  in.instruments[1] = MountOf(scenario, *hook, physics::InstrumentRole::kCauteryHook);
  return in;
}

std::filesystem::path BemCachePath(const Scenario& scenario) {
  std::filesystem::path dir;
  if (const char* v = std::getenv("VESICA_CACHE_DIR"); v != nullptr && *v != '\0') {
    dir = v;
  } else if (const char* x = std::getenv("XDG_CACHE_HOME"); x != nullptr && *x != '\0') {
    dir = std::filesystem::path(x) / "vesica";
  } else if (const char* home = std::getenv("HOME"); home != nullptr && *home != '\0') {
    dir = std::filesystem::path(home) / ".cache" / "vesica";
  } else {
    dir = std::filesystem::temp_directory_path() / "vesica-cache";
  }
  const std::size_t h = std::hash<std::string>{}(std::filesystem::absolute(scenario.liver.surface_mesh).string());
  return dir /
         ("liver-" + scenario.liver.surface_mesh.stem().string() + "-" + std::to_string(h % 1000000007u) + ".greens");
}

void WarnOncePerProcess(const std::string& message) {
  // Opening the same scenario again (Session > Open scenario...) must not repeat the warning.
  static std::mutex mutex;
  static std::set<std::string> said;
  std::lock_guard lock(mutex);
  if (said.insert(message).second) spdlog::warn("{}", message);
}

std::shared_ptr<const physics::DissectionModel> BuildDissectionModelFor(const Scenario& scenario,
                                                                        const SceneMeshes& meshes) {
  physics::DissectionModelInputs in = MakeDissectionInputs(scenario, meshes);
  const std::filesystem::path cache = BemCachePath(scenario);
  std::error_code ec;
  std::filesystem::create_directories(cache.parent_path(), ec);
  if (!ec) {
    in.liver_bem.cache_path = cache.string();
  } else {
    WarnOncePerProcess("BEM cache folder " + cache.parent_path().string() + ": cannot be created (" + ec.message() +
                       "); running without the cache (each start computes the liver's Green's functions again)");
  }
  in.liver_bem.on_warning = WarnOncePerProcess;
  in.liver_bem.on_progress = [last = -1](physics::BemPrecomputeStage stage, double fraction) mutable {
    // Every 20 % of the assembly and the solve's start and end: a few lines, never minutes of silence.
    const int step = static_cast<int>(fraction * 5.0);
    if (stage == physics::BemPrecomputeStage::kAssembly && step == last) return;
    last = stage == physics::BemPrecomputeStage::kAssembly ? step : -1;
    spdlog::info("liver BEM precompute: {} {:.0f} %", physics::ToString(stage), 100.0 * fraction);
  };
  return physics::BuildDissectionModel(in);
}

fx::CauteryParams DefaultCauteryParams() {
  fx::CauteryParams p;
  p.membrane.fade_rate_per_s = 4.0;
  // A plume that hinders the view as real diathermy smoke does (so the resident learns to pause):
  // puffs of 4 mm growing to 2.5 cm over their 1.5 s; positions and lifetimes as fx's defaults.
  p.smoke.initial_size_m = 0.004;
  p.smoke.growth_mps = 0.014;
  return p;
}

}  // namespace vesica::app

namespace vesica::app {

std::optional<CalotSessionSetup> CalotSessionSetupFor(const Scenario& scenario, double aspect) {
  if (!scenario.calot_triangle) return std::nullopt;
  CalotSessionSetup setup;
  setup.triangle = *scenario.calot_triangle;
  const ScopePose scope = ScopePoseOf(scenario.laparoscope);
  setup.camera.p_Eye_W_m = scope.eye_W;
  setup.camera.forward_W = scope.forward_W;
  setup.camera.up_W = scope.up_W;
  setup.camera.vertical_view_angle_rad = scenario.laparoscope.view_angle_deg * std::numbers::pi / 180.0;
  setup.camera.aspect = aspect;
  return setup;
}

}  // namespace vesica::app
