#include "device/latency_statistics.h"

#include <algorithm>
#include <cmath>

namespace vesica::device {

LatencyStatistics::LatencyStatistics(std::size_t capacity) : ring_(std::max<std::size_t>(capacity, 1)) {}

void LatencyStatistics::Add(std::int64_t duration_ns) {
  ring_[next_] = duration_ns;
  next_ = (next_ + 1) % ring_.size();
  count_ = std::min(count_ + 1, ring_.size());
  ++total_;
}

void LatencyStatistics::Clear() {
  next_ = 0;
  count_ = 0;
  total_ = 0;
}

LatencyStatistics::Summary LatencyStatistics::Summarize() const {
  Summary s;
  s.count = count_;
  s.total = total_;
  if (count_ == 0) return s;
  std::vector<std::int64_t> sorted(ring_.begin(), ring_.begin() + static_cast<std::ptrdiff_t>(count_));
  std::sort(sorted.begin(), sorted.end());
  // Nearest-rank percentile: the smallest sample with at least p of the window at or below it.
  auto rank = [&](double p) {
    const auto k = static_cast<std::size_t>(std::ceil(p * static_cast<double>(count_)));
    return static_cast<double>(sorted[std::clamp<std::size_t>(k, 1, count_) - 1]);
  };
  s.min_ns = static_cast<double>(sorted.front());
  s.max_ns = static_cast<double>(sorted.back());
  s.p50_ns = rank(0.50);
  s.p99_ns = rank(0.99);
  double sum = 0.0;
  for (std::int64_t v : sorted) sum += static_cast<double>(v);
  s.mean_ns = sum / static_cast<double>(count_);
  double var = 0.0;
  for (std::int64_t v : sorted) var += (static_cast<double>(v) - s.mean_ns) * (static_cast<double>(v) - s.mean_ns);
  s.jitter_ns = std::sqrt(var / static_cast<double>(count_));
  return s;
}

}  // namespace vesica::device
