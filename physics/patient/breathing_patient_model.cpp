#include "physics/patient/breathing_patient_model.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <string>

#include "physics/patient/patient_labels.h"

namespace vesica::physics {
namespace label = patient_label;
namespace {

void Require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("breathing patient: " + what);
}

int BlockVoxels(double block_m, const LabelVolume& volume) {
  return std::max(1, static_cast<int>(std::lround(block_m / volume.spacing_m.minCoeff())));
}

void CheckVolume(const LabelVolume& v) {
  Require(v.dims[0] > 0 && v.dims[1] > 0 && v.dims[2] > 0, "the label map is empty");
  Require(v.labels.size() == static_cast<std::size_t>(v.dims[0]) * v.dims[1] * v.dims[2],
          "the label map's size does not match its dimensions");
  Require(v.spacing_m.minCoeff() > 0.0 && v.spacing_m.allFinite(), "the label map's spacing must be > 0");
  Require((v.direction.transpose() * v.direction - Eigen::Matrix3d::Identity()).norm() < 1e-6,
          "the label map's direction matrix is not orthonormal");
}

DiaphragmModel BuildDiaphragm(const LabelVolume& v, const BreathingPatientParameters& p) {
  DiaphragmModel d;
  d.lattice = BuildBlockLattice(v, BlockVoxels(p.diaphragm_block_m, v), label::IsDiaphragm, "diaphragm");
  const int n = d.lattice.size();
  std::vector<int> tendon_voxels(static_cast<std::size_t>(n), 0);
  std::vector<std::uint8_t> attached(static_cast<std::size_t>(n), 0);
  d.pleural.assign(static_cast<std::size_t>(n), 0);
  const auto& dims = v.dims;
  for (int k = 0; k < dims[2]; ++k)
    for (int j = 0; j < dims[1]; ++j)
      for (int i = 0; i < dims[0]; ++i) {
        const std::uint8_t l = v.At(i, j, k);
        if (!label::IsDiaphragm(l)) continue;
        const auto e = static_cast<std::size_t>(d.lattice.ElementOfVoxel(i, j, k));
        if (l == label::kDiaphragmTendon) ++tendon_voxels[e];
        for (int dk = -1; dk <= 1; ++dk)
          for (int dj = -1; dj <= 1; ++dj)
            for (int di = -1; di <= 1; ++di) {
              const int a = i + di, b = j + dj, c = k + dk;
              if (a < 0 || b < 0 || c < 0 || a >= dims[0] || b >= dims[1] || c >= dims[2]) continue;
              const std::uint8_t around = v.At(a, b, c);
              if (around == label::kSpine) attached[e] = 1;
              if (around == label::kLung || around == label::kCostophrenicRecess) d.pleural[e] = 1;
            }
      }
  d.mail = std::make_shared<ChainMail>(n, p.diaphragm_mail);
  d.lattice.LinkInto(*d.mail, v);
  for (int e = 0; e < n; ++e) {
    const auto ue = static_cast<std::size_t>(e);
    if (attached[ue]) {
      d.spine_attachment.push_back(e);
      d.mail->Fix(e);
    } else if (2 * tendon_voxels[ue] > d.lattice.voxel_count[ue]) {
      d.tendon.push_back(e);
    }
  }
  Require(!d.tendon.empty(),
          "the diaphragm has no central tendon (label " + std::to_string(label::kDiaphragmTendon) + ")");
  Require(!d.spine_attachment.empty(), "the diaphragm does not touch the spine (its crura are fixed there)");
  d.rise_over_crura_m = d.mail->SlackFrom(d.spine_attachment, 2, false);
  d.rise_over_tendon_m = d.mail->SlackFrom(d.tendon, 2, false);
  d.held = d.tendon;
  d.held.insert(d.held.end(), d.spine_attachment.begin(), d.spine_attachment.end());
  // How far the tendon may go along z before a fixed element would have to follow.
  d.max_tendon_displacement_m = INFINITY;
  for (bool raise : {true, false}) {
    const std::vector<double> slack = d.mail->SlackFrom(d.tendon, 2, raise);
    for (int f : d.spine_attachment)
      d.max_tendon_displacement_m = std::min(d.max_tendon_displacement_m, slack[static_cast<std::size_t>(f)]);
  }
  return d;
}

LiverModel BuildLiver(const LabelVolume& v, const DiaphragmModel& diaphragm, const BreathingPatientParameters& p) {
  LiverModel liver;
  liver.lattice = BuildBlockLattice(v, BlockVoxels(p.liver_block_m, v), label::IsLiver, "liver");
  const int n = liver.lattice.size();
  liver.mail = std::make_shared<ChainMail>(n, p.liver_mail);
  liver.lattice.LinkInto(*liver.mail, v, 6);
  for (int e = 0; e < n; ++e)
    if (liver.lattice.neighbour_count[static_cast<std::size_t>(e)] < 26) liver.capsule.push_back(e);  // on the surface

  // Coupling (seed 4.5): liver voxels closer than the threshold to a diaphragm voxel.
  std::vector<std::map<int, int>> pairs(static_cast<std::size_t>(n));
  const double threshold2 = p.coupling_threshold_m * p.coupling_threshold_m;
  const auto& dims = v.dims;
  int reach[3];
  for (int c = 0; c < 3; ++c) reach[c] = static_cast<int>(std::ceil(p.coupling_threshold_m / v.spacing_m(c)));
  Eigen::Vector3d tumour_sum = Eigen::Vector3d::Zero();
  int tumour_voxels = 0;
  for (int k = 0; k < dims[2]; ++k)
    for (int j = 0; j < dims[1]; ++j)
      for (int i = 0; i < dims[0]; ++i) {
        const std::uint8_t l = v.At(i, j, k);
        if (l == label::kTumour) {
          tumour_sum += v.Position(i, j, k);
          ++tumour_voxels;
        }
        if (!label::IsDiaphragm(l)) continue;
        const int dia = diaphragm.lattice.ElementOfVoxel(i, j, k);
        for (int c = std::max(0, k - reach[2]); c <= std::min(dims[2] - 1, k + reach[2]); ++c)
          for (int b = std::max(0, j - reach[1]); b <= std::min(dims[1] - 1, j + reach[1]); ++b)
            for (int a = std::max(0, i - reach[0]); a <= std::min(dims[0] - 1, i + reach[0]); ++a) {
              if (!label::IsLiver(v.At(a, b, c))) continue;
              const Eigen::Vector3d d((a - i) * v.spacing_m.x(), (b - j) * v.spacing_m.y(), (c - k) * v.spacing_m.z());
              if (d.squaredNorm() >= threshold2) continue;
              ++pairs[static_cast<std::size_t>(liver.lattice.ElementOfVoxel(a, b, c))][dia];
            }
      }
  for (int e = 0; e < n; ++e) {
    const auto& to = pairs[static_cast<std::size_t>(e)];
    if (to.empty()) continue;
    LiverCoupling coupling{e, {}, {}};
    int total = 0;
    for (const auto& [dia, count] : to) total += count;
    for (const auto& [dia, count] : to) {
      coupling.diaphragm_elements.push_back(dia);
      coupling.weights.push_back(static_cast<float>(count) / static_cast<float>(total));
    }
    liver.coupling.push_back(std::move(coupling));
  }
  Require(!liver.coupling.empty(), "no liver voxel lies within the coupling threshold of the diaphragm");
  liver.under_first.push_back(0);
  for (int e = 0; e < n; ++e) {
    const Eigen::Vector3d& l = liver.lattice.rest_m[static_cast<std::size_t>(e)];
    for (int d = 0; d < diaphragm.lattice.size(); ++d) {
      const Eigen::Vector3d gap = diaphragm.lattice.rest_m[static_cast<std::size_t>(d)] - l;
      if (!diaphragm.pleural[static_cast<std::size_t>(d)] || gap.z() <= 0.0 || gap.head<2>().norm() >= p.under_radius_m)
        continue;
      liver.under_diaphragm.push_back(d);
      liver.under_allowance_m.push_back(gap.z() - std::min(gap.z(), p.under_clearance_m));
    }
    liver.under_first.push_back(static_cast<int>(liver.under_diaphragm.size()));
  }
  if (tumour_voxels > 0) {
    liver.has_tumour = true;
    liver.tumour_centre_m = tumour_sum / tumour_voxels;
    liver.tumour = EmbedPoints(liver.lattice, v, {liver.tumour_centre_m});
  }
  return liver;
}

}  // namespace

void ValidateBreathingPatientParameters(const BreathingPatientParameters& p) {
  ValidateRespirationSettings(p.respiration);
  Require(p.diaphragm_block_m > 0.0, "diaphragm_block_m must be > 0");
  Require(p.liver_block_m > 0.0, "liver_block_m must be > 0");
  ValidateChainMailParameters(p.diaphragm_mail, "diaphragm");
  ValidateChainMailParameters(p.liver_mail, "liver");
  Require(p.coupling_threshold_m > 0.0, "coupling_threshold_m must be > 0");
  Require(p.coupling_stiffness_N_per_m > 0.0, "coupling_stiffness_N_per_m must be > 0");
  Require(p.liver_support_stiffness_N_per_m >= 0.0, "liver_support_stiffness_N_per_m must be >= 0");
  Require(p.under_radius_m > 0.0, "under_radius_m must be > 0");
  Require(p.under_clearance_m >= 0.0, "under_clearance_m must be >= 0");
}

std::shared_ptr<const BreathingPatientModel> BuildBreathingPatientModel(LabelVolume volume,
                                                                        const BreathingPatientParameters& parameters) {
  ValidateBreathingPatientParameters(parameters);
  CheckVolume(volume);
  auto model = std::make_shared<BreathingPatientModel>();
  model->parameters = parameters;
  model->volume = std::move(volume);
  const LabelVolume& v = model->volume;

  std::vector<Eigen::Vector3d> spine;
  std::vector<std::vector<Eigen::Vector3d>> ribs(2 * label::kMaxRib);
  for (int k = 0; k < v.dims[2]; ++k)
    for (int j = 0; j < v.dims[1]; ++j)
      for (int i = 0; i < v.dims[0]; ++i) {
        const std::uint8_t l = v.At(i, j, k);
        if (l == label::kSpine) spine.push_back(v.Position(i, j, k));
        for (int side = 0; side < 2; ++side)
          if (l > label::Rib(side == 1, 0) && l <= label::Rib(side == 1, label::kMaxRib))
            ribs[static_cast<std::size_t>(side * label::kMaxRib + l - label::Rib(side == 1, 1))].push_back(
                v.Position(i, j, k));
      }
  Require(!spine.empty(), "the label map has no spine (label " + std::to_string(label::kSpine) + ")");
  model->spine = SpineAxisFromVoxels(spine, v.VoxelVolume_m3());
  for (int side = 0; side < 2; ++side)
    for (int n = 1; n <= label::kMaxRib; ++n) {
      const auto& voxels = ribs[static_cast<std::size_t>(side * label::kMaxRib + n - 1)];
      if (!voxels.empty()) model->ribs.push_back(BuildRibModel(side == 1, n, voxels, v.VoxelVolume_m3(), model->spine));
    }
  model->diaphragm = BuildDiaphragm(v, parameters);
  model->liver = BuildLiver(v, model->diaphragm, parameters);
  return model;
}

}  // namespace vesica::physics
