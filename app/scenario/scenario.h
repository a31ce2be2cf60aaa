#pragma once
// The scenario a session runs: which meshes, materials, fixed regions, trocars, instruments and
// inputs. Plain data, SI units (key names in the file carry their unit: *_m, *_Pa, *_deg ...).
// Loaded and checked by LoadScenario (scenario_loader.h); the file format is docs/scenario.md.

#include <Eigen/Core>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "app/scenario/assistant_retraction_config.h"
#include "app/scenario/calot_triangle_config.h"
#include "app/scenario/patient_position.h"
#include "physics/instrument/instrument_tool.h"

namespace vesica::app {

/// Linear isotropic material. E > 0 (Pa), -1 < nu < 0.5, density > 0 (kg/m^3).
struct Material {
  double youngs_modulus_Pa = 0;
  double poisson_ratio = 0;
  double density_kg_per_m3 = 1000;
};

/// The liver: a boundary-element body on a closed surface whose labelled vertices are fixed.
struct LiverConfig {
  std::filesystem::path surface_mesh;  ///< absolute (resolved against the scenario file)
  Material material;
};

enum class FemElement { kLinear, kCorotational };
/// kPcg: block-Jacobi PCG, at most 20 iterations (the paper); kCholmod: sparse Cholesky refactored
/// each step (exact); kRotatedFactorPcg: PCG preconditioned by the rest system's factor turned into
/// each node's current frame (converged, factorised once).
enum class FemSolver { kPcg, kCholmod, kRotatedFactorPcg };

/// The gallbladder: a finite-element body on a tetrahedral mesh.
struct GallbladderConfig {
  std::filesystem::path volume_mesh;
  Material material;
  FemElement element = FemElement::kCorotational;
  FemSolver solver = FemSolver::kPcg;
  double rayleigh_mass = 0.1;        ///< alpha in D = alpha M + beta K (1/s)
  double rayleigh_stiffness = 0.01;  ///< beta (s)
};

/// Springs and membranes binding the gallbladder to its bed (gallbladder paper §2.4).
struct ConnectiveTissueConfig {
  double stiffness_N_per_m = 0;
  double damping_Ns_per_m = 0;
  double attach_offset_m = 0;  ///< how far the gallbladder is offset toward the liver to find springs
};

struct AbdominalWallConfig {
  std::filesystem::path surface_mesh;
  double opacity = 0.15;  ///< 0 hides the wall, 1 is opaque
};

/// A port through the abdominal wall; each instrument pivots about its trocar's remote centre.
struct Trocar {
  std::string name;
  Eigen::Vector3d position_m = Eigen::Vector3d::Zero();
};

struct LaparoscopeConfig {
  Eigen::Vector3d position_m = Eigen::Vector3d::Zero();  ///< the port (remote centre) on the abdominal wall
  Eigen::Vector3d look_at_m = Eigen::Vector3d::Zero();
  double insertion_m = 0.07;    ///< the scope's tip (camera and light) this far in from the port, toward look_at
  double view_angle_deg = 70;   ///< vertical field of view
  double scope_angle_deg = 30;  ///< angled-scope tip (0 or 30 degrees in practice)
};

/// grasper, cautery_hook at the start of a case; clip_applier and scissors by exchange.
using InstrumentKind = physics::InstrumentTool;
/// What drives an instrument: keyboard/mouse, a recorded session, or a CAN arm (emulated or real).
enum class InputKind { kKeyboard, kReplay, kEmulatedArm, kCanArm };

struct InstrumentConfig {
  std::string name;
  InstrumentKind kind = InstrumentKind::kGrasper;
  std::string trocar;  ///< name of a Trocar
  /// Tools this port's instrument is exchanged for during the case, in the order a press of the
  /// exchange key or the arm's handle button brings them (then back to `kind`). Right hand only.
  std::vector<InstrumentKind> exchange;
  InputKind input = InputKind::kKeyboard;
  std::filesystem::path replay_file;  ///< when input is replay
  std::string can_interface;          ///< when input is can_arm, e.g. "can0"
  int can_node_id = 0;
  double shaft_length_m = 0.36;
  double shaft_radius_m = 0.0025;
  double initial_insertion_m = 0.10;  ///< tip depth below the remote centre at start
};

/// A static organ drawn for context, not simulated (the duodenum, the colon, the omentum, the
/// bile ducts and the cystic artery, fat): a tube along its points, or an ellipsoid.
struct ContextOrgan {
  enum class Shape { kTube, kEllipsoid };
  std::string name;
  Shape shape = Shape::kTube;
  std::vector<Eigen::Vector3d> points_m;                  ///< tube centreline, >= 2 points
  double radius_m = 0;                                    ///< tube radius
  Eigen::Vector3d centre_m = Eigen::Vector3d::Zero();     ///< ellipsoid
  Eigen::Vector3d semi_axes_m = Eigen::Vector3d::Zero();  ///< ellipsoid, along x, y, z
  Eigen::Vector3d rgb = Eigen::Vector3d::Constant(0.8);   ///< colour 0..1
  /// The gallbladder rests on it (a static obstacle in the physics). Default: true for an
  /// ellipsoid and a tube of radius >= kSolidTubeRadius_m (bowel), false for thinner tubes.
  bool solid = false;
};

/// Tubes at least this thick are solid unless the scenario says otherwise (duodenum, colon).
inline constexpr double kSolidTubeRadius_m = 0.008;

struct Scenario {
  std::filesystem::path source;  ///< the file it was loaded from
  std::string name;
  std::string description;
  LiverConfig liver;
  GallbladderConfig gallbladder;
  ConnectiveTissueConfig connective_tissue;
  AbdominalWallConfig abdominal_wall;
  std::vector<Trocar> trocars;
  LaparoscopeConfig laparoscope;
  std::vector<InstrumentConfig> instruments;
  std::vector<ContextOrgan> context_organs;                       ///< optional [[context_organs]]
  PatientPosition patient;                                        ///< optional [patient]: gravity on the gallbladder
  std::optional<AssistantRetractionConfig> assistant_retraction;  ///< optional [assistant_retraction]
  std::optional<CalotTriangleConfig> calot_triangle;              ///< optional [calot_triangle]: the Calot step

  const Trocar& trocar(const std::string& name) const;
};

}  // namespace vesica::app
