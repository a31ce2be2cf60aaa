#include "app/session/session_recording_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <system_error>

namespace vesica::app {

std::string SafeFileNamePart(const std::string& text) {
  std::string safe;
  for (const char c : text) {
    const bool keep = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '.' ||
                      c == '-' || c == '_';
    safe += keep ? c : '_';
  }
  if (safe.find_first_not_of('.') == std::string::npos) return "trainee";  // "", ".", ".."
  return safe;
}

std::filesystem::path CreateSessionRecordingFile(const std::filesystem::path& dir, const std::string& trainee_id,
                                                 std::int64_t started_unix_s) {
  std::error_code error;
  std::filesystem::create_directories(dir, error);
  if (error) throw std::runtime_error("recordings folder " + dir.string() + ": cannot be created: " + error.message());
  const std::string stem = SafeFileNamePart(trainee_id) + "-session-" + std::to_string(started_unix_s);
  for (int n = 1; n < 10000; ++n) {
    const std::filesystem::path path = dir / (stem + (n > 1 ? "-" + std::to_string(n) : "") + ".csv");
    const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
    if (fd >= 0) {
      ::close(fd);
      return path;
    }
    if (errno != EEXIST) throw std::runtime_error(path.string() + ": cannot be created: " + std::strerror(errno));
  }
  throw std::runtime_error("recordings folder " + dir.string() + ": 9999 recordings named " + stem + " already");
}

}  // namespace vesica::app
