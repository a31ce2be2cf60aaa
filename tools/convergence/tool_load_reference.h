#pragma once
// Reads a converged continuum reference written by tools/convergence/reference.py (issue 37):
//   prescribed_m ux uy uz   the tool's displacement of its footprint (m)
//   force_N fx fy fz        the total reaction on the footprint (N)
//   contact i j ...         the trainer vertices in the footprint
//   u i ux uy uz            displacement (m) of trainer vertex i, one line each
//   centre_m, jaw_long_axis (grasp only) the jaw's centre (m) and its long side
// '#' lines are comments. Errors name the file and line.

#include <Eigen/Core>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "physics/mesh/mesh_types.h"

namespace vesica::convergence {

struct ToolLoadReference {
  Eigen::Vector3d prescribed_m = Eigen::Vector3d::Zero();
  Eigen::Vector3d force_N = Eigen::Vector3d::Zero();
  std::vector<int> contact;
  Eigen::Vector3d centre_m = Eigen::Vector3d::Zero();       ///< grasp only: the jaw's centre
  Eigen::Vector3d jaw_long_axis = Eigen::Vector3d::Zero();  ///< grasp only: its long side (unit)
  physics::Vertices displacement_m;                         ///< #V x 3, trainer vertex order
};

inline ToolLoadReference ReadToolLoadReference(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot open the reference (made by tools/convergence/reference.py)");
  ToolLoadReference ref;
  std::vector<Eigen::Vector3d> u;
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream words(line);
    std::string tag;
    words >> tag;
    const auto fail = [&](const std::string& why) {
      return std::runtime_error(path + ":" + std::to_string(number) + ": " + why);
    };
    if (tag == "prescribed_m" || tag == "force_N" || tag == "centre_m" || tag == "jaw_long_axis") {
      Eigen::Vector3d& v = tag == "force_N"         ? ref.force_N
                           : tag == "centre_m"      ? ref.centre_m
                           : tag == "jaw_long_axis" ? ref.jaw_long_axis
                                                    : ref.prescribed_m;
      if (!(words >> v.x() >> v.y() >> v.z())) throw fail(tag + " needs three numbers");
    } else if (tag == "contact") {
      for (int i; words >> i;) ref.contact.push_back(i);
    } else if (tag == "u") {
      int i;
      Eigen::Vector3d d;
      if (!(words >> i >> d.x() >> d.y() >> d.z())) throw fail("u needs a vertex and three numbers");
      if (i != static_cast<int>(u.size())) throw fail("u lines must list the vertices in order");
      u.push_back(d);
    } else {
      throw fail("unknown entry '" + tag + "'");
    }
  }
  if (u.empty() || ref.contact.empty()) throw std::runtime_error(path + ": no displacements or no contact vertices");
  ref.displacement_m.resize(static_cast<Eigen::Index>(u.size()), 3);
  for (std::size_t i = 0; i < u.size(); ++i) ref.displacement_m.row(static_cast<Eigen::Index>(i)) = u[i].transpose();
  return ref;
}

}  // namespace vesica::convergence
