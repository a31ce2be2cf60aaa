#pragma once
// Binary cache of the precomputed Green's functions. Layout (native byte order):
//   "VESBEMGF" | u32 format version | u64 key | u64 rows | u64 cols | rows*cols f64 (column-major)
//   | u64 checksum of everything before it.
// The key hashes mesh + material + boundary + quadrature; a file whose magic, version, key, size
// or checksum disagrees is reported and never trusted. The cache is only an optimisation: a file
// that cannot be read or written is reported (BemPrecomputeOptions::on_warning) and the model is
// computed instead.

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <string>

namespace vesica::physics {

enum class GreensCacheStatus {
  kLoaded,      ///< file valid for this key
  kMissing,     ///< no file there
  kStale,       ///< valid file for another mesh, material, boundary or format version
  kCorrupt,     ///< truncated, wrong magic or checksum mismatch
  kUnreadable,  ///< something is there but cannot be read (a directory, no permission, I/O error)
};
const char* ToString(GreensCacheStatus status);

/// 64-bit hash of a byte range, continuing from `seed` (chained to hash several fields).
std::uint64_t HashBytes(const void* data, std::size_t size, std::uint64_t seed);

/// Reads the matrix stored under `key`; returns it only when status is kLoaded. `reason`
/// (optional) receives the system's reason when status is kUnreadable.
std::optional<Eigen::MatrixXd> ReadGreensCache(const std::string& path, std::uint64_t key,
                                               GreensCacheStatus& status, std::string* reason = nullptr);

/// Writes atomically: a temporary file of a name unique to this call (`path`.tmp-XXXXXX, so that
/// two processes filling the cache at once do not share one) renamed over `path`. On any failure
/// (no folder, read-only or full disk, `path` a directory) the temporary file is removed and
/// BemError names the path and the system's reason.
void WriteGreensCache(const std::string& path, std::uint64_t key, const Eigen::MatrixXd& greens);

}  // namespace vesica::physics
