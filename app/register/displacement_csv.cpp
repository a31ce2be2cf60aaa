#include "app/register/displacement_csv.h"

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "app/register/control_point_csv.h"

namespace vesica::app::registration {

namespace {
[[noreturn]] void Fail(const std::filesystem::path& file, int line, const std::string& what) {
  throw RegisterInputError(file.string() + ":" + std::to_string(line) + ": " + what);
}
}  // namespace

physics::DisplacementSeries ReadDisplacementSeries(const std::filesystem::path& file,
                                                   const physics::TetrahedralMesh& rest) {
  std::ifstream in(file);
  if (!in) throw RegisterInputError(file.string() + ": cannot be opened");
  std::vector<physics::DisplacementFrame> frames;
  std::vector<int> frame_numbers, first_lines;
  std::vector<std::vector<char>> seen;
  std::string text;
  int line = 0;
  while (std::getline(in, text)) {
    ++line;
    if (line == 1) {
      if (text != "frame,time_s,node,ux_m,uy_m,uz_m")
        Fail(file, line, "expected the header frame,time_s,node,ux_m,uy_m,uz_m");
      continue;
    }
    if (text.empty()) continue;
    std::vector<double> v;
    std::stringstream split(text);
    for (std::string f; std::getline(split, f, ',');) {
      std::size_t used = 0;
      double value = 0.0;
      try {
        value = std::stod(f, &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used == 0 || used != f.size() || !std::isfinite(value))
        Fail(file, line, "'" + f + "' is not a finite number");
      v.push_back(value);
    }
    if (v.size() != 6) Fail(file, line, "expected 6 fields, found " + std::to_string(v.size()));
    const int frame = static_cast<int>(v[0]);
    const int node = static_cast<int>(v[2]);
    if (node < 0 || node >= rest.num_vertices() || v[2] != node)
      Fail(file, line,
           "node " + std::to_string(v[2]) + " is not one of the mesh's " + std::to_string(rest.num_vertices()));
    if (frames.empty() || frame_numbers.back() != frame) {
      if (!frames.empty() && !(v[1] > frames.back().time_s)) Fail(file, line, "time does not ascend with the frames");
      frames.push_back({v[1], physics::Vertices::Zero(rest.num_vertices(), 3)});
      frame_numbers.push_back(frame);
      first_lines.push_back(line);
      seen.emplace_back(static_cast<size_t>(rest.num_vertices()), 0);
    }
    if (seen.back()[static_cast<size_t>(node)])
      Fail(file, line, "node " + std::to_string(node) + " twice in its frame");
    seen.back()[static_cast<size_t>(node)] = 1;
    frames.back().displacement_m.row(node) << v[3], v[4], v[5];
  }
  if (frames.empty()) throw RegisterInputError(file.string() + ": no displacements");
  for (size_t f = 0; f < frames.size(); ++f)
    for (char s : seen[f])
      if (!s) Fail(file, first_lines[f], "frame " + std::to_string(frame_numbers[f]) + " does not list every node");
  return physics::DisplacementSeries(rest, std::move(frames));
}

}  // namespace vesica::app::registration
