#pragma once
// The meshes a scenario names, loaded and validated through the VTK adapter.

#include "app/scenario/scenario.h"
#include "physics/mesh/tetrahedral_mesh.h"
#include "physics/mesh/triangle_mesh.h"

namespace vesica::app {

struct SceneMeshes {
  physics::TriangleMesh liver;                ///< closed, labelled surface
  physics::TetrahedralMesh gallbladder;       ///< volume
  physics::TriangleMesh gallbladder_surface;  ///< boundary of the volume
  physics::TriangleMesh abdominal_wall;       ///< open surface
};

/// Throws physics::MeshError naming the file and element when a mesh is unusable.
SceneMeshes LoadSceneMeshes(const Scenario& scenario);

}  // namespace vesica::app
