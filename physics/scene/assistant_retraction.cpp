#include "physics/scene/assistant_retraction.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace vesica::physics {

namespace {
void Require(bool ok, const std::string& field, const std::string& rule) {
  if (!ok) throw std::invalid_argument("assistant retraction: " + field + " " + rule);
}
}  // namespace

AssistantRetraction MakeAssistantRetraction(const TetrahedralMesh& rest_mesh, const AssistantRetractionSettings& s) {
  AssistantRetraction r;
  if (!s.enabled) return r;
  Require(s.grasp_point_m.allFinite(), "grasp_point_m", "must be finite");
  Require(s.displacement_m.allFinite(), "displacement_m", "must be finite");
  Require(std::isfinite(s.radius_m) && s.radius_m > 0, "radius_m", "must be > 0");
  Require(std::isfinite(s.stiffness_N_per_m) && s.stiffness_N_per_m > 0, "stiffness_N_per_m", "must be > 0");
  Require(std::isfinite(s.damping_Ns_per_m) && s.damping_Ns_per_m >= 0, "damping_Ns_per_m", "must be >= 0");
  for (int v = 0; v < rest_mesh.num_vertices(); ++v)
    if ((rest_mesh.vertices.row(v).transpose() - s.grasp_point_m).norm() <= s.radius_m) r.nodes.push_back(v);
  Require(!r.nodes.empty(), "grasp_point_m",
          "holds no gallbladder node (none within radius_m = " + std::to_string(s.radius_m) + " m)");
  r.targets_m.resize(static_cast<Eigen::Index>(r.nodes.size()), 3);
  for (size_t k = 0; k < r.nodes.size(); ++k)
    r.targets_m.row(static_cast<Eigen::Index>(k)) = rest_mesh.vertices.row(r.nodes[k]) + s.displacement_m.transpose();
  r.stiffness_N_per_m = s.stiffness_N_per_m;
  r.damping_Ns_per_m = s.damping_Ns_per_m;
  return r;
}

void AddRetractionStiffness(const AssistantRetraction& r, Eigen::VectorXd& k, Eigen::VectorXd& c) {
  for (int node : r.nodes) {
    k.segment<3>(3 * node).array() += r.stiffness_N_per_m;
    c.segment<3>(3 * node).array() += r.damping_Ns_per_m;
  }
}

void AddRetractionForces(const AssistantRetraction& r, const Vertices& x, const Eigen::VectorXd& v,
                         Eigen::VectorXd& f) {
  for (size_t k = 0; k < r.nodes.size(); ++k) {
    const int node = r.nodes[k];
    const Eigen::Vector3d stretch = r.targets_m.row(static_cast<Eigen::Index>(k)) - x.row(node);
    f.segment<3>(3 * node) += r.stiffness_N_per_m * stretch - r.damping_Ns_per_m * v.segment<3>(3 * node);
  }
}

double RetractionEnergy(const AssistantRetraction& r, const Vertices& x) {
  double e = 0;
  for (size_t k = 0; k < r.nodes.size(); ++k)
    e += 0.5 * r.stiffness_N_per_m * (r.targets_m.row(static_cast<Eigen::Index>(k)) - x.row(r.nodes[k])).squaredNorm();
  return e;
}

}  // namespace vesica::physics
