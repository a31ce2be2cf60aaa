#include "physics/bem/greens_function_cache.h"

#include <cstdio>
#include <cstring>
#include <fstream>
#include <vector>

#include "physics/bem/bem_errors.h"

namespace vesica::physics {
namespace {

constexpr char kMagic[8] = {'V', 'E', 'S', 'B', 'E', 'M', 'G', 'F'};
constexpr std::uint32_t kFormatVersion = 1;
constexpr std::size_t kHeaderBytes = sizeof(kMagic) + sizeof(std::uint32_t) + 3 * sizeof(std::uint64_t);

}  // namespace

const char* ToString(GreensCacheStatus status) {
  switch (status) {
    case GreensCacheStatus::kLoaded: return "loaded";
    case GreensCacheStatus::kMissing: return "missing";
    case GreensCacheStatus::kStale: return "stale";
    case GreensCacheStatus::kCorrupt: return "corrupt";
  }
  return "unknown";
}

std::uint64_t HashBytes(const void* data, std::size_t size, std::uint64_t seed) {
  // Word-wise multiply-rotate mixing (xxHash64 primes) with a murmur finaliser: fast enough to
  // check hundreds of megabytes and sensitive to any flipped bit.
  constexpr std::uint64_t k1 = 0x9E3779B185EBCA87ULL, k2 = 0xC2B2AE3D27D4EB4FULL;
  auto rotl = [](std::uint64_t x, int r) { return (x << r) | (x >> (64 - r)); };
  const auto* bytes = static_cast<const unsigned char*>(data);
  std::uint64_t h = seed ^ (size * k1);
  std::size_t i = 0;
  for (; i + 8 <= size; i += 8) {
    std::uint64_t w;
    std::memcpy(&w, bytes + i, 8);
    h = rotl(h ^ (w * k2), 31) * k1;
  }
  std::uint64_t tail = 0;
  std::memcpy(&tail, bytes + i, size - i);
  h = rotl(h ^ (tail * k2), 31) * k1;
  h ^= h >> 33;
  h *= 0xff51afd7ed558ccdULL;
  h ^= h >> 33;
  h *= 0xc4ceb9fe1a85ec53ULL;
  h ^= h >> 33;
  return h;
}

std::optional<Eigen::MatrixXd> ReadGreensCache(const std::string& path, std::uint64_t key,
                                               GreensCacheStatus& status) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    status = GreensCacheStatus::kMissing;
    return std::nullopt;
  }
  char header[kHeaderBytes];
  if (!in.read(header, kHeaderBytes) || std::memcmp(header, kMagic, sizeof(kMagic)) != 0) {
    status = GreensCacheStatus::kCorrupt;
    return std::nullopt;
  }
  std::uint32_t version;
  std::uint64_t stored_key, rows, cols;
  std::memcpy(&version, header + 8, 4);
  std::memcpy(&stored_key, header + 12, 8);
  std::memcpy(&rows, header + 20, 8);
  std::memcpy(&cols, header + 28, 8);
  if (version != kFormatVersion || stored_key != key) {
    status = GreensCacheStatus::kStale;
    return std::nullopt;
  }
  in.seekg(0, std::ios::end);
  const auto file_bytes = static_cast<std::uint64_t>(in.tellg());
  if (rows > (1u << 20) || cols > (1u << 20) ||
      file_bytes != kHeaderBytes + rows * cols * sizeof(double) + sizeof(std::uint64_t)) {
    status = GreensCacheStatus::kCorrupt;
    return std::nullopt;
  }
  in.seekg(static_cast<std::streamoff>(kHeaderBytes));
  Eigen::MatrixXd greens(static_cast<Eigen::Index>(rows), static_cast<Eigen::Index>(cols));
  std::uint64_t checksum = 0;
  in.read(reinterpret_cast<char*>(greens.data()),
          static_cast<std::streamsize>(rows * cols * sizeof(double)));
  in.read(reinterpret_cast<char*>(&checksum), sizeof(checksum));
  const std::uint64_t expected = HashBytes(greens.data(), rows * cols * sizeof(double),
                                           HashBytes(header, kHeaderBytes, 0));
  if (!in || checksum != expected) {
    status = GreensCacheStatus::kCorrupt;
    return std::nullopt;
  }
  status = GreensCacheStatus::kLoaded;
  return greens;
}

void WriteGreensCache(const std::string& path, std::uint64_t key, const Eigen::MatrixXd& greens) {
  char header[kHeaderBytes];
  const std::uint64_t rows = static_cast<std::uint64_t>(greens.rows());
  const std::uint64_t cols = static_cast<std::uint64_t>(greens.cols());
  std::memcpy(header, kMagic, 8);
  std::memcpy(header + 8, &kFormatVersion, 4);
  std::memcpy(header + 12, &key, 8);
  std::memcpy(header + 20, &rows, 8);
  std::memcpy(header + 28, &cols, 8);
  const std::size_t data_bytes = rows * cols * sizeof(double);
  const std::uint64_t checksum =
      HashBytes(greens.data(), data_bytes, HashBytes(header, kHeaderBytes, 0));
  const std::string temporary = path + ".tmp";
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    out.write(header, kHeaderBytes);
    out.write(reinterpret_cast<const char*>(greens.data()), static_cast<std::streamsize>(data_bytes));
    out.write(reinterpret_cast<const char*>(&checksum), sizeof(checksum));
    if (!out) throw BemError(temporary + ": cannot write the BEM Green's function cache");
  }
  if (std::rename(temporary.c_str(), path.c_str()) != 0)
    throw BemError(path + ": cannot move the BEM Green's function cache into place");
}

}  // namespace vesica::physics
