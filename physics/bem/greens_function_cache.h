#pragma once
// Binary cache of the precomputed Green's functions. Layout (native byte order):
//   "VESBEMGF" | u32 format version | u64 key | u64 rows | u64 cols | rows*cols f64 (column-major)
//   | u64 checksum of everything before it.
// The key hashes mesh + material + boundary + quadrature; a file whose magic, version, key, size
// or checksum disagrees is reported and never trusted.

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <string>

namespace vesica::physics {

enum class GreensCacheStatus {
  kLoaded,     ///< file valid for this key
  kMissing,    ///< no file (or unreadable)
  kStale,      ///< valid file for another mesh, material, boundary or format version
  kCorrupt,    ///< truncated, wrong magic or checksum mismatch
};
const char* ToString(GreensCacheStatus status);

/// 64-bit hash of a byte range, continuing from `seed` (chained to hash several fields).
std::uint64_t HashBytes(const void* data, std::size_t size, std::uint64_t seed);

/// Reads the matrix stored under `key`; returns it only when status is kLoaded.
std::optional<Eigen::MatrixXd> ReadGreensCache(const std::string& path, std::uint64_t key,
                                               GreensCacheStatus& status);

/// Writes atomically (temporary file + rename). Throws BemError naming the path on I/O failure.
void WriteGreensCache(const std::string& path, std::uint64_t key, const Eigen::MatrixXd& greens);

}  // namespace vesica::physics
