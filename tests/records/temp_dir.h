#pragma once
// A fresh folder under /tmp, removed with everything in it when the object goes.

#include <filesystem>

namespace vesica::app::testing {

class TempDir {
 public:
  explicit TempDir(const char* prefix = "vesica-records");
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

}  // namespace vesica::app::testing
