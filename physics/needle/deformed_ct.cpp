#include "physics/needle/deformed_ct.h"

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "physics/patient/patient_labels.h"

namespace vesica::physics {
namespace label = patient_label;
namespace {

constexpr double kFillerHu = 40.0;  // a moving organ's rest voxels, vacated: soft tissue (issue 33's HU)
constexpr int kInversionSteps = 3;  // q = p - u(q): the lattices' displacement varies slowly, 3 steps converge

// The 8 voxels around continuous index v and their trilinear weights; corners outside the grid
// get index SIZE_MAX (air).
struct Corners {
  std::size_t index[8];
  double weight[8];
};
Corners TrilinearCorners(const LabelVolume& volume, const Eigen::Vector3d& v) {
  Corners c;
  const int i0 = static_cast<int>(std::floor(v.x())), j0 = static_cast<int>(std::floor(v.y())),
            k0 = static_cast<int>(std::floor(v.z()));
  const double fx = v.x() - i0, fy = v.y() - j0, fz = v.z() - k0;
  const double wx[2] = {1 - fx, fx}, wy[2] = {1 - fy, fy}, wz[2] = {1 - fz, fz};
  const int* d = volume.dims.data();
  const bool interior = i0 >= 0 && j0 >= 0 && k0 >= 0 && i0 + 1 < d[0] && j0 + 1 < d[1] && k0 + 1 < d[2];
  const std::size_t sx = 1, sy = static_cast<std::size_t>(d[0]), sz = sy * static_cast<std::size_t>(d[1]);
  const std::size_t base = interior ? volume.Index(i0, j0, k0) : 0;
  int n = 0;
  for (int dk = 0; dk < 2; ++dk)
    for (int dj = 0; dj < 2; ++dj)
      for (int di = 0; di < 2; ++di, ++n) {
        c.weight[n] = wx[di] * wy[dj] * wz[dk];
        if (interior) {
          c.index[n] = base + di * sx + dj * sy + dk * sz;
          continue;
        }
        const int i = i0 + di, j = j0 + dj, k = k0 + dk;
        const bool in = i >= 0 && j >= 0 && k >= 0 && i < d[0] && j < d[1] && k < d[2];
        c.index[n] = in ? volume.Index(i, j, k) : std::numeric_limits<std::size_t>::max();
      }
  return c;
}
std::size_t NearestCorner(const Corners& c) {
  return static_cast<std::size_t>(std::max_element(std::begin(c.weight), std::end(c.weight)) - std::begin(c.weight));
}

// Chebyshev distance in blocks to the nearest block holding an element, capped at 255.
std::vector<std::uint8_t> BlockReach(const BlockLattice& lattice) {
  const auto& d = lattice.block_dims;
  std::vector<std::uint8_t> reach(lattice.element_of_block.size(), 255);
  std::vector<std::size_t> frontier, next;
  for (std::size_t b = 0; b < reach.size(); ++b)
    if (lattice.element_of_block[b] >= 0) {
      reach[b] = 0;
      frontier.push_back(b);
    }
  for (int level = 1; level < 255 && !frontier.empty(); ++level) {
    next.clear();
    for (std::size_t b : frontier) {
      const int bi = static_cast<int>(b % d[0]), bj = static_cast<int>((b / d[0]) % d[1]),
                bk = static_cast<int>(b / (static_cast<std::size_t>(d[0]) * d[1]));
      for (int dk = -1; dk <= 1; ++dk)
        for (int dj = -1; dj <= 1; ++dj)
          for (int di = -1; di <= 1; ++di) {
            const int i = bi + di, j = bj + dj, k = bk + dk;
            if (i < 0 || j < 0 || k < 0 || i >= d[0] || j >= d[1] || k >= d[2]) continue;
            const std::size_t n = static_cast<std::size_t>(i + d[0] * (j + d[1] * k));
            if (reach[n] != 255) continue;
            reach[n] = static_cast<std::uint8_t>(level);
            next.push_back(n);
          }
    }
    std::swap(frontier, next);
  }
  return reach;
}

bool InBox(const Eigen::Vector3d& p, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, double margin) {
  return p.x() >= lo.x() - margin && p.y() >= lo.y() - margin && p.z() >= lo.z() - margin && p.x() <= hi.x() + margin &&
         p.y() <= hi.y() + margin && p.z() <= hi.z() + margin;
}

}  // namespace

std::shared_ptr<const DeformedCtModel> BuildDeformedCtModel(std::shared_ptr<const BreathingPatientModel> patient,
                                                            const std::vector<std::int16_t>& hu) {
  if (!patient) throw std::invalid_argument("deformed CT: no patient model");
  const LabelVolume& v = patient->volume;
  if (hu.size() != v.labels.size())
    throw std::invalid_argument("deformed CT: the CT has " + std::to_string(hu.size()) + " voxels, the label map " +
                                std::to_string(v.labels.size()));
  auto m = std::make_shared<DeformedCtModel>();
  m->patient = patient;
  m->hu.assign(hu.begin(), hu.end());
  m->to_index = (v.direction * v.spacing_m.asDiagonal()).inverse();
  m->min_spacing_m = v.spacing_m.minCoeff();
  const std::size_t ribs = patient->ribs.size();
  // Rib r of the model: its bone, cartilage and bundle move together.
  std::uint8_t body_of_label[256] = {};
  for (int l = 0; l < 256; ++l) {
    const auto u8 = static_cast<std::uint8_t>(l);
    if (label::IsLiver(u8)) body_of_label[l] = kLiverBody;
    if (label::IsDiaphragm(u8)) body_of_label[l] = kDiaphragmBody;
    const label::RibOf rib = label::RibOfLabel(u8);
    if (rib.number == 0) continue;
    for (std::size_t r = 0; r < ribs; ++r)
      if (patient->ribs[r].left == rib.left && patient->ribs[r].number == rib.number)
        body_of_label[l] = static_cast<std::uint8_t>(kFirstRibBody + r);
  }
  const Eigen::Vector3d big = Eigen::Vector3d::Constant(1e9);
  m->liver_lo_m = m->diaphragm_lo_m = big;
  m->liver_hi_m = m->diaphragm_hi_m = -big;
  m->rib_lo_m.assign(ribs, big);
  m->rib_hi_m.assign(ribs, -big);
  m->body.resize(v.labels.size());
  for (int k = 0; k < v.dims[2]; ++k)
    for (int j = 0; j < v.dims[1]; ++j)
      for (int i = 0; i < v.dims[0]; ++i) {
        const std::size_t q = v.Index(i, j, k);
        const std::uint8_t b = body_of_label[v.labels[q]];
        m->body[q] = b;
        if (b == kStillBody) continue;
        const Eigen::Vector3d p = v.Position(i, j, k);
        Eigen::Vector3d& lo = b == kLiverBody       ? m->liver_lo_m
                              : b == kDiaphragmBody ? m->diaphragm_lo_m
                                                    : m->rib_lo_m[b - kFirstRibBody];
        Eigen::Vector3d& hi = b == kLiverBody       ? m->liver_hi_m
                              : b == kDiaphragmBody ? m->diaphragm_hi_m
                                                    : m->rib_hi_m[b - kFirstRibBody];
        lo = lo.cwiseMin(p);
        hi = hi.cwiseMax(p);
      }
  if (ribs > 32) throw std::invalid_argument("deformed CT: more than 32 ribs");
  // Each rib's cells, dilated by one cell.
  constexpr int kCell = DeformedCtModel::kRibCellVoxels;
  for (int c = 0; c < 3; ++c) m->rib_cell_dims[c] = (v.dims[c] + kCell - 1) / kCell;
  const auto& cd = m->rib_cell_dims;
  const auto cell_index = [&](int ci, int cj, int ck) {
    return static_cast<std::size_t>(ci + cd[0] * (cj + cd[1] * ck));
  };
  m->rib_cells.assign(static_cast<std::size_t>(cd[0]) * cd[1] * cd[2], 0);
  for (int k = 0; k < v.dims[2]; ++k)
    for (int j = 0; j < v.dims[1]; ++j)
      for (int i = 0; i < v.dims[0]; ++i) {
        const std::uint8_t b = m->body[v.Index(i, j, k)];
        if (b < kFirstRibBody) continue;
        const std::uint32_t bit = 1u << (b - kFirstRibBody);
        const int ci = i / kCell, cj = j / kCell, ck = k / kCell;
        for (int dk = -1; dk <= 1; ++dk)
          for (int dj = -1; dj <= 1; ++dj)
            for (int di = -1; di <= 1; ++di) {
              const int a = ci + di, bb = cj + dj, cc = ck + dk;
              if (a < 0 || bb < 0 || cc < 0 || a >= cd[0] || bb >= cd[1] || cc >= cd[2]) continue;
              m->rib_cells[cell_index(a, bb, cc)] |= bit;
            }
      }
  {  // Each rib's cells dilated by its reach (and a cell, for where in its cell a point lies).
    const int reach_cells = static_cast<int>(std::ceil(DeformedCtModel::kRibReach_m / (kCell * m->min_spacing_m))) + 1;
    m->rib_reach_cells.assign(m->rib_cells.size(), 0);
    for (int ck = 0; ck < cd[2]; ++ck)
      for (int cj = 0; cj < cd[1]; ++cj)
        for (int ci = 0; ci < cd[0]; ++ci) {
          std::uint32_t bits = 0;
          for (int dk = -reach_cells; dk <= reach_cells; ++dk)
            for (int dj = -reach_cells; dj <= reach_cells; ++dj)
              for (int di = -reach_cells; di <= reach_cells; ++di) {
                const int a = ci + di, bb = cj + dj, cc = ck + dk;
                if (a < 0 || bb < 0 || cc < 0 || a >= cd[0] || bb >= cd[1] || cc >= cd[2]) continue;
                bits |= m->rib_cells[cell_index(a, bb, cc)];
              }
          m->rib_reach_cells[cell_index(ci, cj, ck)] = bits;
        }
  }
  m->liver_block_reach = BlockReach(patient->liver.lattice);
  m->diaphragm_block_reach = BlockReach(patient->diaphragm.lattice);
  return m;
}

DeformedCt::DeformedCt(std::shared_ptr<const DeformedCtModel> model) : model_(std::move(model)) {
  if (!model_) throw std::invalid_argument("deformed CT: no model");
  const BreathingPatientModel& p = *model_->patient;
  for (BodyState* s : {&prev_, &now_}) {
    s->u_liver.assign(static_cast<std::size_t>(p.liver.lattice.size()), Eigen::Vector3d::Zero());
    s->u_diaphragm.assign(static_cast<std::size_t>(p.diaphragm.lattice.size()), Eigen::Vector3d::Zero());
    s->rib_rotation.assign(p.ribs.size(), Eigen::Matrix3d::Identity());
    s->tumour_m = p.liver.tumour_centre_m;
  }
  SetBlend(1.0);
}

void DeformedCt::SetPatient(const PatientSnapshot& snapshot) {
  const BreathingPatientModel& p = *model_->patient;
  const auto& liver = snapshot.liver_breathing_m.empty() ? snapshot.liver_m : snapshot.liver_breathing_m;
  if (liver.size() != now_.u_liver.size() || snapshot.diaphragm_m.size() != now_.u_diaphragm.size() ||
      snapshot.ribs.size() != now_.rib_rotation.size())
    throw std::invalid_argument("deformed CT: the patient snapshot is of another model");
  // The state blended now becomes the previous one (in place: no allocation on the haptic thread).
  const double w = w_;
  for (std::size_t e = 0; e < prev_.u_liver.size(); ++e)
    prev_.u_liver[e] = (1 - w) * prev_.u_liver[e] + w * now_.u_liver[e];
  for (std::size_t e = 0; e < prev_.u_diaphragm.size(); ++e)
    prev_.u_diaphragm[e] = (1 - w) * prev_.u_diaphragm[e] + w * now_.u_diaphragm[e];
  prev_.rib_rotation = rib_rotation_;
  prev_.tumour_m = (1 - w) * prev_.tumour_m + w * now_.tumour_m;
  prev_.max_u_m = max_u_m_;
  double max_u = 0.0;
  for (std::size_t e = 0; e < liver.size(); ++e) {
    now_.u_liver[e] = liver[e] - p.liver.lattice.rest_m[e];
    max_u = std::max(max_u, now_.u_liver[e].squaredNorm());
  }
  for (std::size_t e = 0; e < snapshot.diaphragm_m.size(); ++e) {
    now_.u_diaphragm[e] = snapshot.diaphragm_m[e] - p.diaphragm.lattice.rest_m[e];
    max_u = std::max(max_u, now_.u_diaphragm[e].squaredNorm());
  }
  for (std::size_t r = 0; r < snapshot.ribs.size(); ++r) now_.rib_rotation[r] = snapshot.ribs[r].rotation;
  now_.tumour_m = snapshot.tumour_centre_m;
  now_.max_u_m = std::sqrt(max_u);
  w_ = 0.0;
  SetBlend(0.0);
}

void DeformedCt::SetBlend(double w) {
  w_ = std::clamp(w, 0.0, 1.0);
  max_u_m_ = std::max(prev_.max_u_m, now_.max_u_m);
  const BreathingPatientModel& p = *model_->patient;
  const std::size_t ribs = p.ribs.size();
  rib_rotation_.resize(ribs);
  rib_box_lo_.resize(ribs);
  rib_box_hi_.resize(ribs);
  ribs_within_reach_ = true;
  for (std::size_t r = 0; r < ribs; ++r) {
    const Eigen::Quaterniond a(prev_.rib_rotation[r]), b(now_.rib_rotation[r]);
    rib_rotation_[r] = a.slerp(w_, b).toRotationMatrix();
    // The rib's box now: its rest box's corners, turned.
    const Eigen::Vector3d& c = p.ribs[r].centre_m;
    const Eigen::Vector3d& lo = model_->rib_lo_m[r];
    const Eigen::Vector3d& hi = model_->rib_hi_m[r];
    Eigen::Vector3d box_lo = Eigen::Vector3d::Constant(1e9), box_hi = -box_lo;
    for (int corner = 0; corner < 8; ++corner) {
      const Eigen::Vector3d q((corner & 1) ? hi.x() : lo.x(), (corner & 2) ? hi.y() : lo.y(),
                              (corner & 4) ? hi.z() : lo.z());
      const Eigen::Vector3d turned = c + rib_rotation_[r] * (q - c);
      box_lo = box_lo.cwiseMin(turned);
      box_hi = box_hi.cwiseMax(turned);
      // |(R - I)(q - c)| is convex in q: its largest over the rib is at a corner of its box.
      if ((turned - q).norm() >= DeformedCtModel::kRibReach_m) ribs_within_reach_ = false;
    }
    rib_box_lo_[r] = box_lo;
    rib_box_hi_[r] = box_hi;
  }
}

Eigen::Vector3d DeformedCt::LatticeDisplacement(const BlockLattice& lattice, const std::vector<Eigen::Vector3d>& u_prev,
                                                const std::vector<Eigen::Vector3d>& u_now,
                                                const Eigen::Vector3d& q) const {
  const LabelVolume& v = model_->patient->volume;
  // Continuous block coordinates: block b's centre is at voxel index (b + 1/2) n - 1/2.
  const double n = lattice.block_voxels;
  const Eigen::Vector3d beta = ((model_->to_index * (q - v.origin_m)).array() + 0.5) / n - 0.5;
  const int b0[3] = {static_cast<int>(std::floor(beta.x())), static_cast<int>(std::floor(beta.y())),
                     static_cast<int>(std::floor(beta.z()))};
  const double f[3] = {beta.x() - b0[0], beta.y() - b0[1], beta.z() - b0[2]};
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  double weight = 0.0;
  for (int corner = 0; corner < 8; ++corner) {
    int b[3];
    double w = 1.0;
    for (int c = 0; c < 3; ++c) {
      const int d = (corner >> c) & 1;
      b[c] = b0[c] + d;
      w *= d ? f[c] : 1 - f[c];
    }
    if (b[0] < 0 || b[1] < 0 || b[2] < 0 || b[0] >= lattice.block_dims[0] || b[1] >= lattice.block_dims[1] ||
        b[2] >= lattice.block_dims[2] || w <= 0.0)
      continue;
    const int e = lattice.element_of_block[static_cast<std::size_t>(b[0] + lattice.block_dims[0] *
                                                                               (b[1] + lattice.block_dims[1] * b[2]))];
    if (e < 0) continue;
    const auto ue = static_cast<std::size_t>(e);
    sum += w * ((1 - w_) * u_prev[ue] + w_ * u_now[ue]);
    weight += w;
  }
  return weight > 0.0 ? Eigen::Vector3d(sum / weight) : Eigen::Vector3d::Zero();
}

bool DeformedCt::MayBeNear(const BlockLattice& lattice, const std::vector<std::uint8_t>& reach,
                           const Eigen::Vector3d& p) const {
  const LabelVolume& v = model_->patient->volume;
  const Eigen::Vector3d idx = model_->to_index * (p - v.origin_m);
  const double n = lattice.block_voxels;
  int b[3];
  for (int c = 0; c < 3; ++c) {
    b[c] = static_cast<int>(std::floor((idx[c] + 0.5) / n));
    if (b[c] < 0 || b[c] >= lattice.block_dims[c]) return true;  // beyond the grid: the box decides
  }
  const double blocks =
      reach[static_cast<std::size_t>(b[0] + lattice.block_dims[0] * (b[1] + lattice.block_dims[1] * b[2]))];
  // An element's voxels lie within its block; one block more for the trilinear reach.
  return (blocks - 2.0) * n * model_->min_spacing_m <= max_u_m_;
}

Eigen::Vector3d DeformedCt::InvertLattice(const BlockLattice& lattice, const std::vector<Eigen::Vector3d>& u_prev,
                                          const std::vector<Eigen::Vector3d>& u_now, const Eigen::Vector3d& p,
                                          bool* warm_valid, Eigen::Vector3d* warm_u) const {
  const bool warm = warm_valid && *warm_valid;
  Eigen::Vector3d q = warm ? Eigen::Vector3d(p - *warm_u) : p;
  Eigen::Vector3d u = Eigen::Vector3d::Zero();
  for (int step = 0; step < (warm ? 1 : kInversionSteps); ++step) {
    u = LatticeDisplacement(lattice, u_prev, u_now, q);
    q = p - u;
  }
  if (warm_valid) {
    *warm_valid = true;
    *warm_u = u;
  }
  return q;
}

Eigen::Vector3d DeformedCt::LiverRestPoint(const Eigen::Vector3d& p_W) const {
  return InvertLattice(model_->patient->liver.lattice, prev_.u_liver, now_.u_liver, p_W);
}

Eigen::Vector3d DeformedCt::LiverWorldPoint(const Eigen::Vector3d& q_rest) const {
  return q_rest + LatticeDisplacement(model_->patient->liver.lattice, prev_.u_liver, now_.u_liver, q_rest);
}

Eigen::Vector3d DeformedCt::TumourCentre_m() const { return (1 - w_) * prev_.tumour_m + w_ * now_.tumour_m; }

CtSample DeformedCt::Sample(const Eigen::Vector3d& p_W, SampleHint* hint) const {
  const DeformedCtModel& m = *model_;
  const BreathingPatientModel& patient = *m.patient;
  const LabelVolume& v = patient.volume;
  constexpr std::size_t kOutside = std::numeric_limits<std::size_t>::max();
  CtSample out;

  // The still organs at p itself.
  const Corners here = TrilinearCorners(v, m.to_index * (p_W - v.origin_m));
  double still_hu = 0.0, still_weight = 0.0;
  for (int c = 0; c < 8; ++c) {
    const std::size_t q = here.index[c];
    const double w = here.weight[c];
    if (q == kOutside) {  // air beyond the scan
      still_hu += w * -1000.0;
      still_weight += w;
      continue;
    }
    if (v.labels[q] != label::kAir) out.body_fraction += w;
    if (m.body[q] == kStillBody) {
      still_hu += w * m.hu[q];
      still_weight += w;
    }
  }
  {
    const std::size_t q = here.index[NearestCorner(here)];
    out.label = q == kOutside ? label::kAir : (m.body[q] == kStillBody ? v.labels[q] : label::kSoftTissue);
  }

  // Each moving body that may be here, at its rest point.
  double occupancy_sum = 0.0, hu_sum = 0.0, best_occupancy = 0.0;
  const auto composite = [&](const Eigen::Vector3d& q_rest, std::uint8_t body) {
    const Corners at = TrilinearCorners(v, m.to_index * (q_rest - v.origin_m));
    double o = 0.0, h = 0.0;
    for (int c = 0; c < 8; ++c) {
      const std::size_t q = at.index[c];
      if (q == kOutside || m.body[q] != body) continue;
      o += at.weight[c];
      h += at.weight[c] * m.hu[q];
    }
    if (o <= 0.0) return 0.0;
    occupancy_sum += o;
    hu_sum += h;
    if (o > 0.5 && o > best_occupancy) {
      best_occupancy = o;
      const std::size_t q = at.index[NearestCorner(at)];
      if (q != kOutside && m.body[q] == body) out.label = v.labels[q];
    }
    return o;
  };
  const double margin = max_u_m_ + 2.0 * v.spacing_m.maxCoeff();
  if (InBox(p_W, m.liver_lo_m, m.liver_hi_m, margin) && MayBeNear(patient.liver.lattice, m.liver_block_reach, p_W))
    out.liver_occupancy = composite(InvertLattice(patient.liver.lattice, prev_.u_liver, now_.u_liver, p_W,
                                                  hint ? &hint->liver : nullptr, hint ? &hint->u_liver_m : nullptr),
                                    kLiverBody);
  if (InBox(p_W, m.diaphragm_lo_m, m.diaphragm_hi_m, margin) &&
      MayBeNear(patient.diaphragm.lattice, m.diaphragm_block_reach, p_W))
    composite(InvertLattice(patient.diaphragm.lattice, prev_.u_diaphragm, now_.u_diaphragm, p_W,
                            hint ? &hint->diaphragm : nullptr, hint ? &hint->u_diaphragm_m : nullptr),
              kDiaphragmBody);
  const double rib_margin = 2.0 * v.spacing_m.maxCoeff();
  std::uint32_t candidates = ~0u;
  if (ribs_within_reach_) {
    const Eigen::Vector3d cell = (m.to_index * (p_W - v.origin_m)).array() / DeformedCtModel::kRibCellVoxels;
    const int ci = static_cast<int>(std::floor(cell.x() + 0.5 / DeformedCtModel::kRibCellVoxels)),
              cj = static_cast<int>(std::floor(cell.y() + 0.5 / DeformedCtModel::kRibCellVoxels)),
              ck = static_cast<int>(std::floor(cell.z() + 0.5 / DeformedCtModel::kRibCellVoxels));
    const auto& cd = m.rib_cell_dims;
    const bool in_grid = ci >= 0 && cj >= 0 && ck >= 0 && ci < cd[0] && cj < cd[1] && ck < cd[2];
    if (in_grid) candidates = m.rib_reach_cells[static_cast<std::size_t>(ci + cd[0] * (cj + cd[1] * ck))];
  }
  for (std::size_t r = 0; r < rib_rotation_.size(); ++r) {
    if (!(candidates & (1u << r))) continue;
    if (!InBox(p_W, rib_box_lo_[r], rib_box_hi_[r], rib_margin)) continue;
    const Eigen::Vector3d& c = patient.ribs[r].centre_m;
    const Eigen::Vector3d q = c + rib_rotation_[r].transpose() * (p_W - c);
    const Eigen::Vector3d cell = (m.to_index * (q - v.origin_m)).array() / DeformedCtModel::kRibCellVoxels;
    const int ci = static_cast<int>(std::floor(cell.x() + 0.5 / DeformedCtModel::kRibCellVoxels)),
              cj = static_cast<int>(std::floor(cell.y() + 0.5 / DeformedCtModel::kRibCellVoxels)),
              ck = static_cast<int>(std::floor(cell.z() + 0.5 / DeformedCtModel::kRibCellVoxels));
    const auto& cd = m.rib_cell_dims;
    if (ci < 0 || cj < 0 || ck < 0 || ci >= cd[0] || cj >= cd[1] || ck >= cd[2]) continue;
    if (!(m.rib_cells[static_cast<std::size_t>(ci + cd[0] * (cj + cd[1] * ck))] & (1u << r))) continue;
    composite(q, static_cast<std::uint8_t>(kFirstRibBody + r));
  }

  // Moving organs over the still ones; at end tidal this is the rest CT's trilinear value.
  if (occupancy_sum >= 1.0) {
    out.hu = hu_sum / occupancy_sum;
  } else {
    const double background = still_weight > 0.0 ? still_hu / still_weight : kFillerHu;
    out.hu = hu_sum + (1.0 - occupancy_sum) * background;
  }
  return out;
}

}  // namespace vesica::physics
