#pragma once
// The laparoscope's view of the scene in VTK: organs shaded with mottled vertex colours and a
// wet specular look under the scope's headlight, the abdominal wall hidden or translucent, and
// the instruments as shafts through their trocars. VTK stays inside the .cpp (pimpl).

#include <filesystem>
#include <memory>
#include <vector>

#include "app/render/scene_meshes.h"
#include "app/scenario/scenario.h"
#include "physics/instrument/instrument_pose.h"

class vtkRenderer;
class vtkRenderWindow;

namespace vesica::app {

/// Colours the view paints organs with (linear RGB 0..1, before lighting); tests classify pixels by them.
inline constexpr double kLiverRgb[3] = {0.55, 0.17, 0.13};
inline constexpr double kGallbladderRgb[3] = {0.30, 0.50, 0.22};

class LaparoscopeView {
 public:
  LaparoscopeView(const Scenario& scenario, const SceneMeshes& meshes);
  ~LaparoscopeView();
  LaparoscopeView(const LaparoscopeView&) = delete;
  LaparoscopeView& operator=(const LaparoscopeView&) = delete;

  vtkRenderer* renderer();

  /// Initial instrument poses: each shaft aimed from its trocar at the laparoscope's target.
  const std::vector<physics::InstrumentPose>& poses() const;
  void SetInstrumentPose(std::size_t instrument, const physics::InstrumentPose& pose);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Renders `frames` frames off-screen (X display required: run under Xvfb in CI) and writes the
/// last one as a PNG. Throws std::runtime_error if the file cannot be written.
void RenderToPng(LaparoscopeView& view, int width, int height, int frames, const std::filesystem::path& png);

}  // namespace vesica::app
