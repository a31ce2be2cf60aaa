#pragma once
// What the laparoscope view draws in one frame: the physics session's snapshot of the deformed
// organs, the burn maps, the connective-tissue membrane, the smoke and the instruments. Plain
// data (no VTK); LaparoscopeView::Update checks the sizes against the scene (ValidateRenderFrame).

#include <Eigen/Core>
#include <cstddef>
#include <string>
#include <vector>

#include "app/render/calot_drawing.h"
#include "physics/instrument/instrument_pose.h"
#include "physics/instrument/instrument_tool.h"
#include "physics/mesh/mesh_types.h"

namespace vesica::app {

/// One smoke puff, drawn as a camera-facing, alpha-blended soft disc.
struct SmokeSprite {
  Eigen::Vector3d p_W = Eigen::Vector3d::Zero();  ///< centre, world frame (m)
  double size_m = 0;   ///< diameter of the puff (m), >= 0
  double alpha = 0;    ///< opacity at its centre, [0,1]; fades to 0 at the rim
};

struct InstrumentFrame {
  physics::InstrumentPose pose;   ///< yaw/pitch/roll/insertion/jaw (jaw 0 = closed)
  bool grasping = false;          ///< jaws holding tissue
  bool slipping = false;          ///< a grasp slipped recently: the jaws are highlighted
  bool cautery_active = false;    ///< hook pedal down and touching: the hook tip glows
  bool pedal_down = false;        ///< the instrument's pedal is pressed (shown in the field, touching or not)
  /// How far the commanded tip lies beyond the first surface its shaft meets (>= 0): the tool is
  /// drawn that much short of pose.insertion_m, never through tissue, and the field says so.
  double past_contact_m = 0;
  /// What the port holds: the right hand's exchanges its hook for the clip applier or scissors.
  physics::InstrumentTool tool = physics::InstrumentTool::kGrasper;
};

/// Sizes below are checked by ValidateRenderFrame; "empty" entries mean "as at rest / untouched".
struct RenderFrame {
  physics::Vertices liver_vertices;        ///< #liver.V x 3 current positions (SceneMeshes::liver numbering); empty = rest
  physics::Vertices gallbladder_vertices;  ///< #boundary.V x 3: physics::ExtractBoundary(meshes.gallbladder).surface numbering; empty = rest
  std::vector<float> liver_burn;           ///< #liver.F, [0,1]: 0 untouched, 1 black; empty = unburned
  std::vector<float> gallbladder_burn;     ///< #boundary.F, [0,1]; empty = unburned
  physics::Vertices membrane_vertices;     ///< connective-tissue membrane points (2 per spring)
  physics::Triangles membrane_triangles;   ///< fixed topology into membrane_vertices (may be empty: no membrane)
  std::vector<float> membrane_opacity;     ///< #membrane_triangles, [0,1]; 0 = removed (not drawn); empty = all 1
  std::vector<float> membrane_burn;        ///< #membrane_triangles, [0,1]; empty = unburned
  std::vector<SmokeSprite> smoke;
  std::vector<InstrumentFrame> instruments;  ///< one per scenario instrument, in scenario order; empty = keep poses
  /// One line per haptic arm for the field's status strip ("left arm ok", "right arm FAULT
  /// overcurrent"); empty when no arm drives the session (keyboard, replay).
  std::vector<std::string> arm_status;
  CalotDrawing calot;  ///< Calot's triangle; empty when the scenario has none
};

/// The scene sizes a frame must match.
struct RenderFrameSizes {
  int liver_vertices = 0;
  int liver_triangles = 0;
  int gallbladder_vertices = 0;   ///< of the boundary surface
  int gallbladder_triangles = 0;  ///< of the boundary surface
  std::size_t instruments = 0;
};

/// Throws std::invalid_argument naming the field (and the sizes, or the bad entry) when `frame`
/// does not fit `sizes`: wrong row counts, membrane indices out of range, non-finite numbers,
/// negative smoke sizes. Burn, opacity and alpha values outside [0,1] are not errors: the view
/// clamps them.
void ValidateRenderFrame(const RenderFrame& frame, const RenderFrameSizes& sizes);

}  // namespace vesica::app
