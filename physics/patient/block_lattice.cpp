#include "physics/patient/block_lattice.h"

#include <Eigen/LU>
#include <cmath>
#include <stdexcept>
#include <string>

namespace vesica::physics {

int BlockLattice::ElementOfVoxel(int i, int j, int k) const {
  const int bi = i / block_voxels, bj = j / block_voxels, bk = k / block_voxels;
  if (i < 0 || j < 0 || k < 0 || bi >= block_dims[0] || bj >= block_dims[1] || bk >= block_dims[2]) return -1;
  return element_of_block[static_cast<std::size_t>(bi + block_dims[0] * (bj + block_dims[1] * bk))];
}

BlockLattice BuildBlockLattice(const LabelVolume& volume, int block_voxels,
                               const std::function<bool(std::uint8_t)>& in_organ, const char* organ) {
  if (block_voxels < 1) throw std::invalid_argument("block lattice: block_voxels must be >= 1");
  BlockLattice lattice;
  lattice.block_voxels = block_voxels;
  for (int c = 0; c < 3; ++c) lattice.block_dims[c] = (volume.dims[c] + block_voxels - 1) / block_voxels;
  const auto& bd = lattice.block_dims;
  lattice.element_of_block.assign(static_cast<std::size_t>(bd[0]) * bd[1] * bd[2], -1);
  for (int k = 0; k < volume.dims[2]; ++k)
    for (int j = 0; j < volume.dims[1]; ++j)
      for (int i = 0; i < volume.dims[0]; ++i) {
        if (!in_organ(volume.At(i, j, k))) continue;
        const int bi = i / block_voxels, bj = j / block_voxels, bk = k / block_voxels;
        int& e = lattice.element_of_block[static_cast<std::size_t>(bi + bd[0] * (bj + bd[1] * bk))];
        if (e < 0) {
          e = lattice.size();
          lattice.block_of.push_back({bi, bj, bk});
          lattice.rest_m.emplace_back(Eigen::Vector3d::Zero());
          lattice.voxel_count.push_back(0);
        }
        lattice.rest_m[static_cast<std::size_t>(e)] += volume.Position(i, j, k);
        ++lattice.voxel_count[static_cast<std::size_t>(e)];
      }
  if (lattice.rest_m.empty()) throw std::invalid_argument(std::string("the label map has no ") + organ);
  for (int e = 0; e < lattice.size(); ++e)
    lattice.rest_m[static_cast<std::size_t>(e)] /= lattice.voxel_count[static_cast<std::size_t>(e)];
  lattice.neighbour_count.assign(lattice.rest_m.size(), 0);
  for (int e = 0; e < lattice.size(); ++e) {
    const auto [bi, bj, bk] = lattice.block_of[static_cast<std::size_t>(e)];
    for (int dk = -1; dk <= 1; ++dk)
      for (int dj = -1; dj <= 1; ++dj)
        for (int di = -1; di <= 1; ++di) {
          if (di == 0 && dj == 0 && dk == 0) continue;
          const int ni = bi + di, nj = bj + dj, nk = bk + dk;
          if (ni < 0 || nj < 0 || nk < 0 || ni >= bd[0] || nj >= bd[1] || nk >= bd[2]) continue;
          if (lattice.element_of_block[static_cast<std::size_t>(ni + bd[0] * (nj + bd[1] * nk))] >= 0)
            ++lattice.neighbour_count[static_cast<std::size_t>(e)];
        }
  }
  return lattice;
}

void BlockLattice::LinkInto(ChainMail& mail, const LabelVolume& volume, int connectivity) const {
  if (connectivity != 6 && connectivity != 26)
    throw std::invalid_argument("block lattice: connectivity must be 6 or 26");
  const Eigen::Vector3d block = volume.spacing_m * block_voxels;
  const auto& bd = block_dims;
  for (int e = 0; e < size(); ++e) {
    const auto [bi, bj, bk] = block_of[static_cast<std::size_t>(e)];
    for (int dk = -1; dk <= 1; ++dk)
      for (int dj = -1; dj <= 1; ++dj)
        for (int di = -1; di <= 1; ++di) {
          // Each pair once: forward offsets only (the first non-zero of dk, dj, di is positive).
          const bool forward = dk > 0 || (dk == 0 && (dj > 0 || (dj == 0 && di > 0)));
          if (!forward || (connectivity == 6 && std::abs(di) + std::abs(dj) + std::abs(dk) != 1)) continue;
          const int ni = bi + di, nj = bj + dj, nk = bk + dk;
          if (ni < 0 || nj < 0 || nk < 0 || ni >= bd[0] || nj >= bd[1] || nk >= bd[2]) continue;
          const int other = element_of_block[static_cast<std::size_t>(ni + bd[0] * (nj + bd[1] * nk))];
          if (other < 0) continue;
          const Eigen::Vector3d step_index(di * block.x(), dj * block.y(), dk * block.z());
          Eigen::Vector3d step = volume.direction * step_index;
          for (int c = 0; c < 3; ++c)  // exact zeros where the lattice does not extend (oblique volumes round)
            if (std::abs(step(c)) < 1e-9 * block.maxCoeff()) step(c) = 0.0;
          mail.Link(e, other, step);
        }
  }
}

Eigen::Vector3d LatticeEmbedding::Displacement(std::size_t p, const std::vector<Eigen::Vector3d>& u) const {
  Eigen::Vector3d d = Eigen::Vector3d::Zero();
  for (int w = first[p]; w < first[p + 1]; ++w)
    d += static_cast<double>(weight[static_cast<std::size_t>(w)]) *
         u[static_cast<std::size_t>(element[static_cast<std::size_t>(w)])];
  return d;
}

LatticeEmbedding EmbedPoints(const BlockLattice& lattice, const LabelVolume& volume,
                             const std::vector<Eigen::Vector3d>& points_m) {
  LatticeEmbedding embedding;
  embedding.first.push_back(0);
  const Eigen::Matrix3d to_index = (volume.direction * volume.spacing_m.asDiagonal()).inverse();
  for (const Eigen::Vector3d& p : points_m) {
    const Eigen::Vector3d ijk = to_index * (p - volume.origin_m);
    const int bi = static_cast<int>(std::floor((ijk.x() + 0.5) / lattice.block_voxels));
    const int bj = static_cast<int>(std::floor((ijk.y() + 0.5) / lattice.block_voxels));
    const int bk = static_cast<int>(std::floor((ijk.z() + 0.5) / lattice.block_voxels));
    const std::size_t start = embedding.element.size();
    double total = 0.0;
    for (int dk = -1; dk <= 1; ++dk)
      for (int dj = -1; dj <= 1; ++dj)
        for (int di = -1; di <= 1; ++di) {
          const int ni = bi + di, nj = bj + dj, nk = bk + dk;
          const auto& bd = lattice.block_dims;
          if (ni < 0 || nj < 0 || nk < 0 || ni >= bd[0] || nj >= bd[1] || nk >= bd[2]) continue;
          const int e = lattice.element_of_block[static_cast<std::size_t>(ni + bd[0] * (nj + bd[1] * nk))];
          if (e < 0) continue;
          const double w = 1.0 / ((p - lattice.rest_m[static_cast<std::size_t>(e)]).squaredNorm() + 1e-8);
          embedding.element.push_back(e);
          embedding.weight.push_back(static_cast<float>(w));
          total += w;
        }
    for (std::size_t w = start; w < embedding.weight.size(); ++w)
      embedding.weight[w] = static_cast<float>(embedding.weight[w] / total);
    embedding.first.push_back(static_cast<int>(embedding.element.size()));
  }
  return embedding;
}

}  // namespace vesica::physics
