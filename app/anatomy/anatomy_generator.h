#pragma once
// The default anatomy of the cholecystectomy scene, generated deterministically from implicit
// shapes: liver surface (labelled), gallbladder tetrahedral meshes at several resolutions with
// their surfaces, the abdominal wall and the trocar ports. See docs/anatomy.md.

#include <filesystem>
#include <string>
#include <vector>

#include "app/anatomy/abdominal_wall_shape.h"
#include "app/anatomy/gallbladder_shape.h"
#include "app/anatomy/liver_labels.h"
#include "app/anatomy/liver_shape.h"
#include "app/anatomy/tet_mesher.h"
#include "app/anatomy/trocar_ports.h"
#include "physics/mesh/mesh_quality.h"

namespace vesica::app::anatomy {

struct GallbladderResolution {
  int target_nodes;      ///< total tet-mesh nodes aimed at
  int surface_vertices;  ///< of the decimated surface TetGen starts from (< target_nodes)
};

struct AnatomyOptions {
  LiverShape liver;
  /// Another liver than `liver`'s wedge (the surgeon's view, surgeon_view_layout.h), sampled over
  /// `liver_field_bounds`; empty: LiverField(liver, gallbladder) over LiverBounds(liver).
  ImplicitField liver_field;
  Box liver_field_bounds{Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
  GallbladderCentreline gallbladder = DefaultGallbladderCentreline();
  LiverLabelRegions liver_labels;
  AbdominalWallShape wall;
  PortSkinPositions ports;

  double liver_voxel_m = 0.0015;  ///< marching-cubes sampling of the liver
  int liver_vertices = 1000;      ///< after decimation
  /// Relaxation rounds of the liver onto its field after decimation (0: none, the default's
  /// liver): vertices back on the exact shape, so a sharp edge is not drawn as a saw.
  int liver_relaxation_iterations = 0;
  /// The liver's edge length (metres) where the relaxation grades it; empty: uniform.
  ImplicitField liver_edge_length_m;
  double gallbladder_voxel_m = 0.0007;  ///< fine enough for the 3 mm cystic duct
  std::vector<GallbladderResolution> gallbladder_resolutions{
      {300, 200}, {600, 370}, {1000, 550}, {1600, 800}, {3000, 1300}};
  /// Tangential relaxation rounds of each gallbladder surface before TetGen (triangle shape).
  int gallbladder_relaxation_iterations = 20;
  TetQualityRequest tet_quality;
  double wall_voxel_m = 0.004;
  int wall_vertices = 800;
  /// Every written coordinate is rounded to this (metres) so files are short and exact on reload.
  double coordinate_resolution_m = 1e-6;
};

struct GallbladderMesh {
  int target_nodes = 0;
  physics::TetrahedralMesh volume;
  physics::TriangleMesh surface;  ///< the boundary of `volume`, outward
  std::string tetgen_switches;
  physics::TetQualitySummary quality;
};

struct AnatomyAssets {
  physics::TriangleMesh liver;  ///< closed, outward, with vertex labels
  std::vector<GallbladderMesh> gallbladders;
  physics::TriangleMesh abdominal_wall;  ///< open dome, normals outward (anterior)
  PortLayout ports;
};

AnatomyAssets GenerateAnatomy(const AnatomyOptions& options);

/// File name stem of a gallbladder resolution, e.g. "gallbladder_300".
std::string GallbladderStem(int target_nodes);

/// Writes liver.vtk, gallbladder_<n>.vtu + gallbladder_<n>_surface.vtk, abdominal_wall.vtk and
/// ports.toml into `directory` (created if missing).
void WriteAnatomy(const AnatomyAssets& assets, const std::filesystem::path& directory);

/// Human-readable table of node counts, volumes and tet quality.
std::string SummariseAnatomy(const AnatomyAssets& assets);

}  // namespace vesica::app::anatomy
