#pragma once
// A small dissection scene with known geometry, for scene tests and benchmarks:
//   liver: a closed box 80 x 40 x 60 mm, y in [0, 40] mm (BEM surface), its
//          top face (y = 40 mm) fixed, its bottom face (y = 0) the gallbladder bed;
//   gallbladder: a 30 x 20 x 30 mm tet box hanging 2 mm under the bed's centre (top face
//          y = -2 mm): 16 springs of 2 mm straight up;
//   instruments: both enter from below (remote centres at y = -80 mm) pointing +y, the grasper
//          at x = -6 mm, the hook at x = +6 mm; the gallbladder's bottom face is at insertion
//          kGallbladderBottomInsertion.

#include <memory>

#include "physics/mesh/primitives.h"
#include "physics/scene/dissection_model.h"

namespace vesica::physics::testing {

inline constexpr double kGallbladderBottomY = -0.022;
inline constexpr double kRemoteCentreY = -0.08;
inline constexpr double kGallbladderBottomInsertion = kGallbladderBottomY - kRemoteCentreY;  // 58 mm
// Both boxes are centred on (kShiftX, kShiftZ), off the instruments' axes x = -+6 mm, z = 0.
inline constexpr double kShiftX = 0.0013, kShiftZ = 0.0017;

inline DissectionModelInputs SyntheticDissectionInputs(int liver_refinement = 1, int gallbladder_cells_per_cm = 1) {
  DissectionModelInputs in;
  // 7 x 5 cells over the bed (11.4 x 12 mm): no gallbladder vertex lies over a grid edge.
  const int c = liver_refinement;
  in.liver_surface = ExtractBoundary(MakeBoxTetMesh({0.08, 0.04, 0.06}, {7 * c, 4 * c, 5 * c})).surface;
  in.liver_surface.vertices.rowwise() += Eigen::RowVector3d(-0.04 + kShiftX, 0.0, -0.03 + kShiftZ);
  in.liver_surface.vertex_labels = Eigen::VectorXi::Zero(in.liver_surface.num_vertices());
  for (int v = 0; v < in.liver_surface.num_vertices(); ++v) {
    const double y = in.liver_surface.vertices(v, 1);
    if (y > 0.04 - 1e-9) in.liver_surface.vertex_labels[v] = kLabelFixed;
    if (y < 1e-9) in.liver_surface.vertex_labels[v] = kLabelGallbladderBed;
  }
  in.liver_source = "synthetic liver box";
  in.liver_material = {170e3, 0.4, 1060.0};

  const int g = gallbladder_cells_per_cm;
  in.gallbladder_mesh = MakeBoxTetMesh({0.03, 0.02, 0.03}, {3 * g, 2 * g, 3 * g});
  in.gallbladder_mesh.vertices.rowwise() += Eigen::RowVector3d(-0.015 + kShiftX, kGallbladderBottomY, -0.015 + kShiftZ);
  in.gallbladder_source = "synthetic gallbladder box";
  in.gallbladder.body_name = "synthetic gallbladder";
  in.gallbladder.material = {20e3, 0.45, 1000.0};
  in.gallbladder.element_model = ElementModel::kCorotational;
  in.gallbladder.solver = LinearSolverKind::kCholmod;
  in.gallbladder.rayleigh_mass_per_s = 1.0;
  in.gallbladder.rayleigh_stiffness_s = 0.01;

  in.instruments[0] = {InstrumentRole::kGrasper, {-0.006, kRemoteCentreY, 0.0}, Eigen::Vector3d::UnitY()};
  in.instruments[1] = {InstrumentRole::kCauteryHook, {0.006, kRemoteCentreY, 0.0}, Eigen::Vector3d::UnitY()};
  return in;
}

}  // namespace vesica::physics::testing
