#include "physics/registration/displacement_series.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace vesica::physics {

DisplacementSeries::DisplacementSeries(TetrahedralMesh rest, std::vector<DisplacementFrame> frames)
    : rest_(std::move(rest)), frames_(std::move(frames)) {
  if (frames_.empty()) throw std::invalid_argument("DisplacementSeries: no frames");
  for (size_t f = 0; f < frames_.size(); ++f) {
    const std::string where = "DisplacementSeries: frame " + std::to_string(f);
    if (frames_[f].displacement_m.rows() != rest_.vertices.rows())
      throw std::invalid_argument(where + " has " + std::to_string(frames_[f].displacement_m.rows()) +
                                  " rows for a mesh of " + std::to_string(rest_.vertices.rows()) + " nodes");
    if (!frames_[f].displacement_m.allFinite() || !std::isfinite(frames_[f].time_s))
      throw std::invalid_argument(where + " is not finite");
    if (f > 0 && !(frames_[f].time_s > frames_[f - 1].time_s))
      throw std::invalid_argument(where + ": time does not ascend");
  }
  if (frames_.size() > 1) {
    const double last_spacing = frames_.back().time_s - frames_[frames_.size() - 2].time_s;
    period_s_ = frames_.back().time_s - frames_.front().time_s + last_spacing;
  }
}

std::vector<TetLocation> DisplacementSeries::Bind(const std::vector<Eigen::Vector3d>& points) const {
  std::vector<TetLocation> out;
  out.reserve(points.size());
  for (const Eigen::Vector3d& p : points) out.push_back(LocateInTetMesh(rest_, p));
  return out;
}

std::vector<Eigen::Vector3d> DisplacementSeries::Sample(const std::vector<TetLocation>& points, double t_s) const {
  // The two frames about t (the last wraps to the first over the final spacing) and the blend.
  size_t a = 0, b = 0;
  double blend = 0.0;
  if (frames_.size() > 1) {
    const double t0 = frames_.front().time_s;
    const double t = t0 + (t_s - t0) - period_s_ * std::floor((t_s - t0) / period_s_);
    const auto after = std::upper_bound(frames_.begin(), frames_.end(), t,
                                        [](double v, const DisplacementFrame& f) { return v < f.time_s; });
    a = static_cast<size_t>(after - frames_.begin()) - 1;
    b = a + 1 < frames_.size() ? a + 1 : 0;
    const double t_b = b == 0 ? t0 + period_s_ : frames_[b].time_s;
    blend = (t - frames_[a].time_s) / (t_b - frames_[a].time_s);
  }
  std::vector<Eigen::Vector3d> out(points.size(), Eigen::Vector3d::Zero());
  for (size_t i = 0; i < points.size(); ++i)
    for (int k = 0; k < 4; ++k) {
      const int node = rest_.tets(points[i].tet, k);
      out[i] += points[i].weights[k] * ((1.0 - blend) * frames_[a].displacement_m.row(node).transpose() +
                                        blend * frames_[b].displacement_m.row(node).transpose());
    }
  return out;
}

std::function<std::vector<Eigen::Vector3d>(double)> MakePointMotion(std::shared_ptr<const DisplacementSeries> series,
                                                                    const std::vector<Eigen::Vector3d>& rest_points_W) {
  if (!series) throw std::invalid_argument("MakePointMotion: no series");
  std::vector<TetLocation> bound = series->Bind(rest_points_W);
  return [series = std::move(series), bound = std::move(bound)](double t_s) { return series->Sample(bound, t_s); };
}

}  // namespace vesica::physics
