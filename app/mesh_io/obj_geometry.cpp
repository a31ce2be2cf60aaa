#include "app/mesh_io/obj_geometry.h"

#include <unistd.h>
#include <vtkOBJReader.h>

#include <cctype>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string_view>

#include "app/mesh_io/vtk_reader_errors.h"
#include "physics/mesh/mesh_validation.h"

namespace vesica::app {

namespace {

namespace fs = std::filesystem;

/// A temporary file holding `text`, removed when this goes out of scope.
class TemporaryFile {
 public:
  explicit TemporaryFile(const std::string& text) {
    std::string name = (fs::temp_directory_path() / "vesica_mesh_XXXXXX").string();
    const int fd = mkstemp(name.data());
    if (fd < 0) throw physics::MeshError(name + ": cannot create a temporary file: " + std::strerror(errno));
    path_ = name;
    const bool written = write(fd, text.data(), text.size()) == static_cast<ssize_t>(text.size());
    close(fd);
    if (!written) throw physics::MeshError(path_.string() + ": cannot write a temporary file");
  }
  ~TemporaryFile() {
    std::error_code ignored;
    fs::remove(path_, ignored);
  }
  TemporaryFile(const TemporaryFile&) = delete;
  TemporaryFile& operator=(const TemporaryFile&) = delete;
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

vtkSmartPointer<vtkPolyData> ReadWithVtk(const fs::path& file, const fs::path& named) {
  auto reader = vtkSmartPointer<vtkOBJReader>::New();
  const VtkReaderErrors errors(reader);
  reader->SetFileName(file.string().c_str());
  reader->Update();
  errors.ThrowIfAny(named);
  return reader->GetOutput();
}

}  // namespace

std::optional<std::string> ObjGeometryOnly(std::istream& obj) {
  std::string text, line;
  bool changed = false;
  while (std::getline(obj, line)) {
    const auto starts = [&](std::string_view keyword) {
      return line.rfind(keyword, 0) == 0 && line.size() > keyword.size() &&
             std::isspace(static_cast<unsigned char>(line[keyword.size()]));
    };
    if (starts("vn") || starts("vt")) {
      line.clear();
      changed = true;
    } else if (starts("f") && line.find('/') != std::string::npos) {
      std::string corners = "f";
      std::istringstream tokens(line.substr(1));
      for (std::string token; tokens >> token;) corners.append(" ").append(token, 0, token.find('/'));
      line = corners;
      changed = true;
    }
    text.append(line).append("\n");
  }
  if (!changed) return std::nullopt;
  return text;
}

vtkSmartPointer<vtkPolyData> ReadObjGeometry(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  const std::optional<std::string> geometry = ObjGeometryOnly(in);
  if (!geometry) return ReadWithVtk(path, path);
  const TemporaryFile copy(*geometry);
  return ReadWithVtk(copy.path(), path);
}

}  // namespace vesica::app
