#pragma once
// Marks the liver surface's regions the simulation treats specially (physics::VertexLabel bits).

#include <Eigen/Core>

#include "app/anatomy/gallbladder_shape.h"
#include "physics/mesh/triangle_mesh.h"

namespace vesica::app::anatomy {

struct LiverLabelRegions {
  /// Bare area and vena cava groove, posterior-superior: an ellipsoid whose surface-crossing
  /// vertices get kLabelFixed. Centre and semi-axes in metres.
  Eigen::Vector3d fixed_centre_m{-0.05, -0.065, 0.085};
  Eigen::Vector3d fixed_semi_axes_m{0.065, 0.035, 0.04};
  /// Vertices closer than this to the gallbladder surface form the bed (kLabelGallbladderBed);
  /// larger than the fossa gap so that the bed covers the fossa up to its rim. Metres.
  double bed_distance_m = 0.009;
};

/// Fills mesh.vertex_labels (overwriting it) from the regions above.
void LabelLiver(physics::TriangleMesh& mesh, const GallbladderCentreline& gallbladder,
                const LiverLabelRegions& regions);

}  // namespace vesica::app::anatomy
