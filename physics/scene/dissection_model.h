#pragma once
// The const part of the cholecystectomy scene (STYLE.md 2): the BEM liver with its Green's
// functions, the FEM gallbladder model and its boundary, the connective tissue as created, the
// instrument mounts and the settings. Built once; DissectionScene holds what changes per step.

#include <array>
#include <memory>
#include <string>

#include "physics/bem/bem_model.h"
#include "physics/collision/surface_proximity_grid.h"
#include "physics/fem/fem_model.h"
#include "physics/mesh/mesh_topology.h"
#include "physics/scene/dissection_settings.h"
#include "physics/scene/static_obstacles.h"
#include "physics/tissue/connective_tissue.h"

namespace vesica::physics {

struct DissectionModel {
  DissectionSettings settings;
  std::array<InstrumentMount, 2> instruments;  ///< [0] left hand (grasper), [1] right hand (hook)
  std::shared_ptr<const BemModel> liver;
  std::shared_ptr<const FemModel> gallbladder;
  TetBoundary gallbladder_boundary;  ///< collision, rendering and cautery surface of the gallbladder
  ConnectiveTissue tissue;           ///< springs and membrane as created (all alive)
  AssistantRetraction retraction;    ///< the fundus's held nodes (empty: no retraction)
  Eigen::Vector3d toward_liver = Eigen::Vector3d::Zero();  ///< unit direction the springs were searched along
  StaticObstacles obstacles;                               ///< organs the gallbladder rests on (static)
  SurfaceProximityGrid liver_proximity;  ///< the liver's surface for the gallbladder's contact (empty: off)
};

struct DissectionModelInputs {
  TriangleMesh liver_surface;  ///< closed, vertex_labels: kLabelFixed held, kLabelGallbladderBed the bed
  std::string liver_source;    ///< for error messages (file name)
  ElasticMaterial liver_material;
  BemPrecomputeOptions liver_bem;
  TetrahedralMesh gallbladder_mesh;
  std::string gallbladder_source;
  FemSettings gallbladder;  ///< its time step is replaced by settings.time_step_s
  /// Gallbladder nodes held in place (none in the trainer, whose gallbladder hangs by the
  /// springs; a held bed compares the scene with a clamped reference, docs/fidelity.md).
  std::vector<DirichletNode> gallbladder_fixed_nodes;
  std::array<InstrumentMount, 2> instruments;
  DissectionSettings settings;
  StaticObstacles obstacles;  ///< the solid context organs (none: the gallbladder rests on nothing but the liver)
};

/// Validates the settings (std::invalid_argument naming the field), builds the liver BEM model
/// (or reads its cache), the gallbladder FEM model (free: held by the springs alone) and the
/// connective tissue (paper §2.4, searched from the gallbladder toward the centroid of the
/// liver's bed-labelled vertices). Throws when no spring can be created.
std::shared_ptr<const DissectionModel> BuildDissectionModel(const DissectionModelInputs& inputs);

}  // namespace vesica::physics
