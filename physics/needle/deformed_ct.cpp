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
  int n = 0;
  for (int dk = 0; dk < 2; ++dk)
    for (int dj = 0; dj < 2; ++dj)
      for (int di = 0; di < 2; ++di, ++n) {
        const int i = i0 + di, j = j0 + dj, k = k0 + dk;
        c.weight[n] = (di ? fx : 1 - fx) * (dj ? fy : 1 - fy) * (dk ? fz : 1 - fz);
        const bool in = i >= 0 && j >= 0 && k >= 0 && i < volume.dims[0] && j < volume.dims[1] && k < volume.dims[2];
        c.index[n] = in ? volume.Index(i, j, k) : std::numeric_limits<std::size_t>::max();
      }
  return c;
}
std::size_t NearestCorner(const Corners& c) {
  return static_cast<std::size_t>(std::max_element(std::begin(c.weight), std::end(c.weight)) - std::begin(c.weight));
}

bool InBox(const Eigen::Vector3d& p, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, double margin) {
  return (p.array() >= lo.array() - margin).all() && (p.array() <= hi.array() + margin).all();
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

void DeformedCt::CaptureBlend(BodyState& out) const {
  const double w = w_;
  for (std::size_t e = 0; e < out.u_liver.size(); ++e)
    out.u_liver[e] = (1 - w) * prev_.u_liver[e] + w * now_.u_liver[e];
  for (std::size_t e = 0; e < out.u_diaphragm.size(); ++e)
    out.u_diaphragm[e] = (1 - w) * prev_.u_diaphragm[e] + w * now_.u_diaphragm[e];
  out.rib_rotation = rib_rotation_;
  out.tumour_m = (1 - w) * prev_.tumour_m + w * now_.tumour_m;
  out.max_u_m = max_u_m_;
}

void DeformedCt::SetPatient(const PatientSnapshot& snapshot) {
  const BreathingPatientModel& p = *model_->patient;
  const auto& liver = snapshot.liver_breathing_m.empty() ? snapshot.liver_m : snapshot.liver_breathing_m;
  if (liver.size() != now_.u_liver.size() || snapshot.diaphragm_m.size() != now_.u_diaphragm.size() ||
      snapshot.ribs.size() != now_.rib_rotation.size())
    throw std::invalid_argument("deformed CT: the patient snapshot is of another model");
  BodyState blended = prev_;  // reuse its storage
  CaptureBlend(blended);
  prev_ = std::move(blended);
  double max_u = 0.0;
  for (std::size_t e = 0; e < liver.size(); ++e) {
    now_.u_liver[e] = liver[e] - p.liver.lattice.rest_m[e];
    max_u = std::max(max_u, now_.u_liver[e].norm());
  }
  for (std::size_t e = 0; e < snapshot.diaphragm_m.size(); ++e) {
    now_.u_diaphragm[e] = snapshot.diaphragm_m[e] - p.diaphragm.lattice.rest_m[e];
    max_u = std::max(max_u, now_.u_diaphragm[e].norm());
  }
  for (std::size_t r = 0; r < snapshot.ribs.size(); ++r) now_.rib_rotation[r] = snapshot.ribs[r].rotation;
  now_.tumour_m = snapshot.tumour_centre_m;
  now_.max_u_m = max_u;
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

Eigen::Vector3d DeformedCt::InvertLattice(const BlockLattice& lattice, const std::vector<Eigen::Vector3d>& u_prev,
                                          const std::vector<Eigen::Vector3d>& u_now, const Eigen::Vector3d& p) const {
  Eigen::Vector3d q = p;
  for (int step = 0; step < kInversionSteps; ++step) q = p - LatticeDisplacement(lattice, u_prev, u_now, q);
  return q;
}

Eigen::Vector3d DeformedCt::LiverRestPoint(const Eigen::Vector3d& p_W) const {
  return InvertLattice(model_->patient->liver.lattice, prev_.u_liver, now_.u_liver, p_W);
}

Eigen::Vector3d DeformedCt::LiverWorldPoint(const Eigen::Vector3d& q_rest) const {
  return q_rest + LatticeDisplacement(model_->patient->liver.lattice, prev_.u_liver, now_.u_liver, q_rest);
}

Eigen::Vector3d DeformedCt::TumourCentre_m() const { return (1 - w_) * prev_.tumour_m + w_ * now_.tumour_m; }

CtSample DeformedCt::Sample(const Eigen::Vector3d& p_W) const {
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
  if (InBox(p_W, m.liver_lo_m, m.liver_hi_m, margin)) out.liver_occupancy = composite(LiverRestPoint(p_W), kLiverBody);
  if (InBox(p_W, m.diaphragm_lo_m, m.diaphragm_hi_m, margin))
    composite(InvertLattice(patient.diaphragm.lattice, prev_.u_diaphragm, now_.u_diaphragm, p_W), kDiaphragmBody);
  const double rib_margin = 2.0 * v.spacing_m.maxCoeff();
  for (std::size_t r = 0; r < rib_rotation_.size(); ++r) {
    if (!InBox(p_W, rib_box_lo_[r], rib_box_hi_[r], rib_margin)) continue;
    const Eigen::Vector3d& c = patient.ribs[r].centre_m;
    composite(c + rib_rotation_[r].transpose() * (p_W - c), static_cast<std::uint8_t>(kFirstRibBody + r));
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
