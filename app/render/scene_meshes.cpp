#include "app/render/scene_meshes.h"

#include "app/mesh_io/mesh_io.h"
#include "physics/mesh/mesh_topology.h"

namespace vesica::app {

SceneMeshes LoadSceneMeshes(const Scenario& scenario) {
  SceneMeshes m;
  m.liver = ReadTriangleMesh(scenario.liver.surface_mesh, physics::SurfaceRequirement::kClosed);
  m.gallbladder = ReadTetrahedralMesh(scenario.gallbladder.volume_mesh);
  m.gallbladder_surface = physics::ExtractBoundary(m.gallbladder).surface;
  physics::ValidateTriangleMesh(m.gallbladder_surface, scenario.gallbladder.volume_mesh.string() + " (boundary)",
                                physics::SurfaceRequirement::kClosed);
  m.abdominal_wall = ReadTriangleMesh(scenario.abdominal_wall.surface_mesh, physics::SurfaceRequirement::kAny);
  return m;
}

}  // namespace vesica::app
