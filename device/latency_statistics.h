#pragma once

#include <cstdint>
#include <vector>

namespace vesica::device {

/// Percentiles of a stream of durations (loop periods, sync-to-state round trips). Keeps the
/// most recent `capacity` samples in a ring allocated once, so Add() is allocation-free in the
/// servo loop; Summary() sorts a copy and belongs outside it.
class LatencyStatistics {
 public:
  explicit LatencyStatistics(std::size_t capacity = 16384);

  void Add(std::int64_t duration_ns);
  void Clear();

  struct Summary {
    std::size_t count = 0;       ///< samples in the window
    std::uint64_t total = 0;     ///< samples ever added
    double min_ns = 0, p50_ns = 0, p99_ns = 0, max_ns = 0, mean_ns = 0;
    double jitter_ns = 0;        ///< standard deviation over the window
  };
  Summary Summarize() const;

 private:
  std::vector<std::int64_t> ring_;
  std::size_t next_ = 0;
  std::size_t count_ = 0;
  std::uint64_t total_ = 0;
};

}  // namespace vesica::device
