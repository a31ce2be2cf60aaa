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
  /// Zero: the whole fossa is the bed. Otherwise only bed vertices whose offset from the nearest
  /// point of the gallbladder's centreline has a component along this unit direction of more
  /// than bed_side_min_m (the surgeon's view: the medial rim, which the physics' springs then
  /// grow toward, so that the membrane lies where the camera and the hook reach it).
  Eigen::Vector3d bed_side_direction = Eigen::Vector3d::Zero();
  double bed_side_min_m = 0;
  /// The same along a second direction (zero: unused), e.g. out of the visceral surface.
  Eigen::Vector3d bed_height_direction = Eigen::Vector3d::Zero();
  double bed_height_min_m = 0;
};

/// Fills mesh.vertex_labels (overwriting it) from the regions above.
void LabelLiver(physics::TriangleMesh& mesh, const GallbladderCentreline& gallbladder,
                const LiverLabelRegions& regions);

}  // namespace vesica::app::anatomy
