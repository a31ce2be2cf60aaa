#include "tests/records/temp_dir.h"

#include <cstdlib>
#include <stdexcept>
#include <string>
#include <system_error>

namespace vesica::app::testing {

TempDir::TempDir(const char* prefix) {
  // /tmp, not $TMPDIR: the PostgreSQL server runs as another user and needs to reach it, and
  // its socket path must stay short (108 bytes).
  std::string pattern = std::string("/tmp/") + prefix + "-XXXXXX";
  if (mkdtemp(pattern.data()) == nullptr) throw std::runtime_error("mkdtemp " + pattern + " failed");
  path_ = pattern;
}

TempDir::~TempDir() {
  std::error_code ignored;
  std::filesystem::remove_all(path_, ignored);
}

}  // namespace vesica::app::testing
