#include "app/anatomy/anatomy_generator.h"

#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "app/anatomy/surface_relaxation.h"
#include "app/mesh_io/mesh_io.h"
#include "physics/mesh/mesh_topology.h"
#include "physics/mesh/mesh_validation.h"

namespace vesica::app::anatomy {

namespace {

using physics::TriangleMesh;

void RoundCoordinates(physics::Vertices& vertices, double resolution_m) {
  // Multiply-round-divide so that the stored doubles are the nearest to short decimals.
  const double scale = std::round(1 / resolution_m);
  vertices = (vertices * scale).array().round() / scale;
}

TriangleMesh MakeLiver(const AnatomyOptions& o) {
  const ImplicitField field =
      o.liver_field ? o.liver_field : [&](const Eigen::Vector3d& p) { return LiverField(o.liver, o.gallbladder, p); };
  const Box bounds = o.liver_field ? o.liver_field_bounds : LiverBounds(o.liver);
  TriangleMesh liver =
      DecimateAndSmooth(ExtractIsosurface(field, bounds, o.liver_voxel_m), {.target_vertices = o.liver_vertices});
  if (o.liver_relaxation_iterations > 0)
    RelaxOntoField(liver, field, o.liver_relaxation_iterations, o.liver_edge_length_m);
  OrientOutward(liver, field);
  RoundCoordinates(liver.vertices, o.coordinate_resolution_m);
  LabelLiver(liver, o.gallbladder, o.liver_labels);
  physics::ValidateTriangleMesh(liver, "generated liver", physics::SurfaceRequirement::kClosed);
  return liver;
}

std::vector<GallbladderMesh> MakeGallbladders(const AnatomyOptions& o) {
  const ImplicitField field = [&](const Eigen::Vector3d& p) { return GallbladderDistance(o.gallbladder, p); };
  const TriangleMesh dense = ExtractIsosurface(field, GallbladderBounds(o.gallbladder, 0.002), o.gallbladder_voxel_m);
  std::vector<GallbladderMesh> meshes;
  for (const GallbladderResolution& resolution : o.gallbladder_resolutions) {
    TriangleMesh surface = DecimateAndSmooth(dense, {.target_vertices = resolution.surface_vertices});
    RelaxOntoField(surface, field, o.gallbladder_relaxation_iterations);
    OrientOutward(surface, field);
    RoundCoordinates(surface.vertices, o.coordinate_resolution_m);
    const std::string stem = GallbladderStem(resolution.target_nodes);
    physics::ValidateTriangleMesh(surface, "generated " + stem + " input surface",
                                  physics::SurfaceRequirement::kClosed);

    SizedTetMesh sized = TetrahedraliseToNodeCount(surface, resolution.target_nodes, o.tet_quality);
    RoundCoordinates(sized.mesh.vertices, o.coordinate_resolution_m);
    physics::ValidateTetrahedralMesh(sized.mesh, "generated " + stem);
    GallbladderMesh mesh;
    mesh.target_nodes = resolution.target_nodes;
    mesh.surface = physics::ExtractBoundary(sized.mesh).surface;
    mesh.quality = physics::MeasureTetQuality(sized.mesh);
    mesh.volume = std::move(sized.mesh);
    mesh.tetgen_switches = sized.switches;
    meshes.push_back(std::move(mesh));
  }
  return meshes;
}

TriangleMesh MakeAbdominalWall(const AnatomyOptions& o) {
  const ImplicitField field = [&](const Eigen::Vector3d& p) { return AbdominalWallField(o.wall, p); };
  // Decimate the closed ellipsoid, then cut the dome off it: quadric decimation leaves open
  // surfaces almost untouched because it will not move their boundary.
  const TriangleMesh ellipsoid = DecimateAndSmooth(
      ExtractIsosurface(field, AbdominalWallBounds(o.wall), o.wall_voxel_m), {.target_vertices = 2 * o.wall_vertices});
  TriangleMesh wall = ClipKeepAbove(ellipsoid, {0, o.wall.base_y_m, 0}, {0, 1, 0});
  OrientOutward(wall, field);
  RoundCoordinates(wall.vertices, o.coordinate_resolution_m);
  physics::ValidateTriangleMesh(wall, "generated abdominal wall", physics::SurfaceRequirement::kAny);
  return wall;
}

Eigen::Vector3d Centroid(const physics::Vertices& vertices) { return vertices.colwise().mean(); }

}  // namespace

std::string GallbladderStem(int target_nodes) { return "gallbladder_" + std::to_string(target_nodes); }

AnatomyAssets GenerateAnatomy(const AnatomyOptions& options) {
  AnatomyAssets assets;
  assets.liver = MakeLiver(options);
  assets.gallbladders = MakeGallbladders(options);
  assets.abdominal_wall = MakeAbdominalWall(options);
  // The laparoscope looks at the gallbladder's middle (finest mesh, the best estimate).
  const Eigen::Vector3d look_at = Centroid(assets.gallbladders.back().surface.vertices);
  assets.ports = PlacePorts(assets.abdominal_wall, options.ports, look_at);
  return assets;
}

void WriteAnatomy(const AnatomyAssets& assets, const std::filesystem::path& directory) {
  std::filesystem::create_directories(directory);
  WriteTriangleMesh(assets.liver, directory / "liver.vtk");
  for (const GallbladderMesh& g : assets.gallbladders) {
    const std::string stem = GallbladderStem(g.target_nodes);
    WriteTetrahedralMesh(g.volume, directory / (stem + ".vtu"));
    WriteTriangleMesh(g.surface, directory / (stem + "_surface.vtk"));
  }
  WriteTriangleMesh(assets.abdominal_wall, directory / "abdominal_wall.vtk");
  WritePortsToml(assets.ports, directory / "ports.toml");
}

std::string SummariseAnatomy(const AnatomyAssets& assets) {
  std::string text;
  char line[256];
  const TriangleMesh& liver = assets.liver;
  auto count_label = [&](int bit) {
    int n = 0;
    for (int i = 0; i < liver.vertex_labels.size(); ++i) n += (liver.vertex_labels[i] & bit) ? 1 : 0;
    return n;
  };
  auto label_area = [&](int bit) {  // triangles with all three corners labelled
    double area = 0;
    for (int f = 0; f < liver.num_triangles(); ++f) {
      bool all = true;
      for (int k = 0; k < 3; ++k) all = all && (liver.vertex_labels[liver.triangles(f, k)] & bit);
      if (all) area += physics::TriangleArea(liver, f);
    }
    return area;
  };
  std::snprintf(line, sizeof line,
                "liver: %d vertices, %d triangles, volume %.1f cm^3, fixed %d vertices (%.1f cm^2), "
                "bed %d vertices (%.1f cm^2)\n",
                liver.num_vertices(), liver.num_triangles(), physics::EnclosedVolume(liver) * 1e6,
                count_label(physics::kLabelFixed), label_area(physics::kLabelFixed) * 1e4,
                count_label(physics::kLabelGallbladderBed), label_area(physics::kLabelGallbladderBed) * 1e4);
  text += line;
  for (const GallbladderMesh& g : assets.gallbladders) {
    std::snprintf(line, sizeof line,
                  "%s: %d nodes (%d on surface), %d tets, volume %.2f cm^3, min dihedral %.2f deg, "
                  "max dihedral %.2f deg, max radius-edge %.3f, mean radius-edge %.3f, tetgen -%s\n",
                  GallbladderStem(g.target_nodes).c_str(), g.volume.num_vertices(), g.surface.num_vertices(),
                  g.volume.num_tets(), physics::TotalVolume(g.volume) * 1e6, g.quality.min_dihedral_deg,
                  g.quality.max_dihedral_deg, g.quality.max_radius_edge, g.quality.mean_radius_edge,
                  g.tetgen_switches.c_str());
    text += line;
  }
  std::snprintf(line, sizeof line, "abdominal wall: %d vertices, %d triangles\n", assets.abdominal_wall.num_vertices(),
                assets.abdominal_wall.num_triangles());
  text += line;
  const auto& p = assets.ports;
  std::snprintf(line, sizeof line,
                "ports (m): grasper (%.4f, %.4f, %.4f), cautery (%.4f, %.4f, %.4f), laparoscope (%.4f, %.4f, %.4f) "
                "looking at (%.4f, %.4f, %.4f)\n",
                p.grasper_m.x(), p.grasper_m.y(), p.grasper_m.z(), p.cautery_m.x(), p.cautery_m.y(), p.cautery_m.z(),
                p.laparoscope_m.x(), p.laparoscope_m.y(), p.laparoscope_m.z(), p.look_at_m.x(), p.look_at_m.y(),
                p.look_at_m.z());
  text += line;
  return text;
}

}  // namespace vesica::app::anatomy
