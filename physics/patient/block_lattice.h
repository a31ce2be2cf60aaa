#pragma once
// A ChainMail lattice over the voxels of one organ: the volume is cut into cubes of
// block_voxels^3 voxels and every cube that holds some of the organ is an element, at the centroid
// of its voxels; elements of touching cubes (26 neighbours) are linked with the cubes' step as
// rest offset. Coarser than the voxels so that one respiration update stays well under 1 ms.

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <functional>
#include <vector>

#include "physics/patient/chain_mail.h"
#include "physics/patient/label_volume.h"

namespace vesica::physics {

struct BlockLattice {
  int block_voxels = 1;
  std::array<int, 3> block_dims{0, 0, 0};
  std::vector<int> element_of_block;         ///< -1 where the cube holds none of the organ
  std::vector<std::array<int, 3>> block_of;  ///< per element, its cube (bi, bj, bk)
  std::vector<Eigen::Vector3d> rest_m;       ///< per element, centroid of its voxels
  std::vector<int> voxel_count;              ///< per element
  std::vector<int> neighbour_count;          ///< per element, linked elements (26 inside the organ)

  [[nodiscard]] int size() const { return static_cast<int>(rest_m.size()); }
  [[nodiscard]] int ElementOfVoxel(int i, int j, int k) const;
  /// Links touching elements into mail (built with size() elements): face neighbours only
  /// (connectivity 6, Gibson's lattice: enough for a solid organ) or all 26 (a thin sloping sheet
  /// such as the diaphragm is only connected through edges and corners).
  void LinkInto(ChainMail& mail, const LabelVolume& volume, int connectivity = 26) const;
};

/// Elements where in_organ(label) holds. Throws std::invalid_argument naming `organ` when none.
[[nodiscard]] BlockLattice BuildBlockLattice(const LabelVolume& volume, int block_voxels,
                                             const std::function<bool(std::uint8_t)>& in_organ, const char* organ);

/// Weights that carry a point (a mesh vertex) with the lattice: the elements of the point's cube
/// and its neighbours, by inverse distance at rest. Empty when no element is near.
struct LatticeEmbedding {
  std::vector<int> element;
  std::vector<float> weight;
  std::vector<int> first;  ///< per point, offsets into element/weight (size points + 1)
  /// Displacement of point p given the elements' displacements.
  [[nodiscard]] Eigen::Vector3d Displacement(std::size_t p, const std::vector<Eigen::Vector3d>& u) const;
};
[[nodiscard]] LatticeEmbedding EmbedPoints(const BlockLattice& lattice, const LabelVolume& volume,
                                           const std::vector<Eigen::Vector3d>& points_m);

}  // namespace vesica::physics
