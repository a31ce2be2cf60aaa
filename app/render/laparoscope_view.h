#pragma once
// The laparoscope's view of the scene in VTK: organs in physically based materials (or Phong,
// material_model.h) with mottled colours, relief and a wet look under the scope's light, which
// leaves the scope beside the lens (scope_light.h) so that the instruments cast shadows on the
// organs; the abdominal wall hidden or translucent, and the instruments (fenestrated grasper,
// L-hook) through their trocars. Update() shows one physics snapshot: the deformed organs, burns,
// the connective-tissue membrane, smoke and the instruments' jaws. VTK stays inside the .cpp.

#include <filesystem>
#include <memory>
#include <vector>

#include "app/render/material_model.h"
#include "app/render/render_colours.h"
#include "app/render/render_frame.h"
#include "app/render/scene_meshes.h"
#include "app/scenario/scenario.h"
#include "physics/instrument/instrument_pose.h"

class vtkRenderer;
class vtkRenderWindow;

namespace vesica::app {

class FieldStatusOverlay;

class LaparoscopeView {
 public:
  /// The gallbladder is drawn from physics::ExtractBoundary(meshes.gallbladder).surface, the
  /// numbering RenderFrame::gallbladder_vertices uses.
  LaparoscopeView(const Scenario& scenario, const SceneMeshes& meshes,
                  MaterialModel materials = MaterialModelFromEnvironment());
  ~LaparoscopeView();
  LaparoscopeView(const LaparoscopeView&) = delete;
  LaparoscopeView& operator=(const LaparoscopeView&) = delete;

  vtkRenderer* renderer();
  MaterialModel materials() const;

  /// Instrument shadows on the organs (on by default).
  void ShowInstrumentShadows(bool on);
  /// The grasp, pedal and arm labels in the field (their text, for tests).
  const FieldStatusOverlay& status() const;

  /// Initial instrument poses: each shaft aimed from its trocar at the laparoscope's target.
  const std::vector<physics::InstrumentPose>& poses() const;
  void SetInstrumentPose(std::size_t instrument, const physics::InstrumentPose& pose);

  /// The sizes Update() expects (liver, gallbladder boundary, instruments).
  const RenderFrameSizes& frame_sizes() const;

  /// Shows one snapshot (takes effect at the next Render of the window). Throws
  /// std::invalid_argument naming the field and sizes when the frame does not fit the scene
  /// (ValidateRenderFrame); the view is then left as it was.
  void Update(const RenderFrame& frame);

  /// The off-screen window RenderToPng draws into: made at the first call and kept (one GL
  /// context for the view's life), resized to width x height.
  vtkRenderWindow* OffscreenWindow(int width, int height);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Renders `frames` frames off-screen (X display required: run under Xvfb in CI) and writes the
/// last one as a PNG. Throws std::runtime_error if the file cannot be written.
void RenderToPng(LaparoscopeView& view, int width, int height, int frames, const std::filesystem::path& png);

}  // namespace vesica::app
