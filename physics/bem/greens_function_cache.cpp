#include "physics/bem/greens_function_cache.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
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
    case GreensCacheStatus::kUnreadable: return "unreadable";
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
                                               GreensCacheStatus& status, std::string* reason) {
  const auto unreadable = [&](const std::string& why) {
    status = GreensCacheStatus::kUnreadable;
    if (reason != nullptr) *reason = why;
    return std::nullopt;
  };
  struct stat info {};
  if (::stat(path.c_str(), &info) != 0) {
    if (errno == ENOENT) {
      status = GreensCacheStatus::kMissing;
      return std::nullopt;
    }
    return unreadable(std::strerror(errno));  // e.g. a path through a file: "Not a directory"
  }
  if (!S_ISREG(info.st_mode)) return unreadable("not a regular file");
  std::ifstream in(path, std::ios::binary);
  if (!in) return unreadable(std::strerror(errno));
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

namespace {

// Writes all of `size` bytes, retrying short writes; false with errno set on failure.
bool WriteAll(int fd, const void* data, std::size_t size) {
  const auto* bytes = static_cast<const char*>(data);
  while (size > 0) {
    const ssize_t written = ::write(fd, bytes, size);
    if (written < 0) {
      if (errno == EINTR) continue;
      return false;
    }
    bytes += written;
    size -= static_cast<std::size_t>(written);
  }
  return true;
}

}  // namespace

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
  const auto fail = [&](const std::string& step) {
    throw BemError(path + ": cannot " + step + " the BEM Green's function cache: " + std::strerror(errno));
  };
  // A name unique to this call: two processes filling an empty cache each write their own file,
  // and the last rename wins with a complete one. A leftover from a killed run is never reused.
  std::string temporary = path + ".tmp-XXXXXX";
  const int fd = ::mkstemp(temporary.data());
  if (fd < 0) fail("create a temporary file for");
  const auto remove_and_fail = [&](const std::string& step) {
    const int saved = errno;
    ::close(fd);
    ::unlink(temporary.c_str());
    errno = saved;
    fail(step);
  };
  ::fchmod(fd, 0644);  // mkstemp's 0600 would hide it from a second account on a shared cache
  if (!WriteAll(fd, header, kHeaderBytes) || !WriteAll(fd, greens.data(), data_bytes) ||
      !WriteAll(fd, &checksum, sizeof(checksum)))
    remove_and_fail("write");
  if (::close(fd) != 0) {
    const int saved = errno;
    ::unlink(temporary.c_str());
    errno = saved;
    fail("write");
  }
  if (std::rename(temporary.c_str(), path.c_str()) != 0) {
    const int saved = errno;
    ::unlink(temporary.c_str());
    errno = saved;
    fail("move into place");
  }
}

}  // namespace vesica::physics
