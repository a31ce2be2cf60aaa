#pragma once
// OBJ surfaces read as the geometry they describe. VTK's OBJ reader gives every face corner a
// point of its own as soon as one corner's normal or texture index differs from its vertex index
// (`f 1//4 2//4 3//4`, as exporters write per-face normals): a closed surface comes out cut open
// along every edge, its vertices renumbered. A surface needs the geometry only, so VTK reads a
// copy whose `f` corners keep their vertex index and whose `vn`/`vt` lines are blank; it then
// keeps the file's vertices in the file's order (`v` line k is vertex k - 1) and its line numbers.

#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <filesystem>
#include <istream>
#include <optional>
#include <string>

namespace vesica::app {

/// The OBJ text with normals and texture coordinates dropped as above (line for line), or
/// nothing when the text has none.
std::optional<std::string> ObjGeometryOnly(std::istream& obj);

/// Reads an OBJ file's vertices and faces with VTK. Throws physics::MeshError naming `path`.
vtkSmartPointer<vtkPolyData> ReadObjGeometry(const std::filesystem::path& path);

}  // namespace vesica::app
