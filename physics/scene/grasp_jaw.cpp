#include "physics/scene/grasp_jaw.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>
#include <stdexcept>

namespace vesica::physics {

GraspJaw::GraspJaw(std::shared_ptr<const FemModel> body, const TetBoundary& boundary, const GraspJawSettings& settings)
    : body_(std::move(body)), boundary_(std::make_shared<const TetBoundary>(boundary)), settings_(settings) {}

GraspJaw::~GraspJaw() = default;  // std::async's futures wait for their workers

std::optional<RectangularFootprint> JawFootprintAt(const TriangleMesh& surface, int triangle,
                                                   const Eigen::Vector3d& weights,
                                                   const Eigen::Vector3d& shaft_direction_W, double length_m,
                                                   double width_m) {
  if (triangle < 0 || triangle >= surface.num_triangles()) return std::nullopt;
  const Eigen::Vector3d a = surface.vertices.row(surface.triangles(triangle, 0)).transpose();
  const Eigen::Vector3d b = surface.vertices.row(surface.triangles(triangle, 1)).transpose();
  const Eigen::Vector3d c = surface.vertices.row(surface.triangles(triangle, 2)).transpose();
  RectangularFootprint jaw;
  jaw.centre_m = weights[0] * a + weights[1] * b + weights[2] * c;
  const Eigen::Vector3d n = (b - a).cross(c - a);
  if (!(n.norm() > 0) || !jaw.centre_m.allFinite()) return std::nullopt;
  jaw.normal = n.normalized();
  const Eigen::Vector3d along = shaft_direction_W - shaft_direction_W.dot(jaw.normal) * jaw.normal;
  jaw.long_axis = along.norm() > 0.2 * shaft_direction_W.norm() ? along.normalized() : jaw.normal.unitOrthogonal();
  jaw.length_m = length_m;
  jaw.width_m = width_m;
  return jaw;
}

bool GraspJaw::Take(int triangle, const Eigen::Vector3d& weights, const Eigen::Vector3d& shaft_direction_W, long step) {
  Release();
  const std::optional<RectangularFootprint> at =
      JawFootprintAt(boundary_->surface, triangle, weights, shaft_direction_W, settings_.length_m, settings_.width_m);
  if (!at) return false;
  const RectangularFootprint jaw = *at;
  FootprintWeights footprint;
  try {
    footprint = ComputeFootprintWeights(*boundary_, jaw);
  } catch (const std::invalid_argument&) {
    return false;
  }
  nodes_ = footprint.nodes;
  weights_.clear();
  for (Eigen::Index i = 0; i < footprint.moments.rows(); ++i)
    weights_.push_back(footprint.moments(i, 0) / footprint.area_m2);
  holding_ = true;
  failure_.clear();
  computed_.reset();
  adopt_step_ = step + settings_.adopt_steps;
  JawSubgridSettings subgrid;
  subgrid.patch_radius_m = settings_.patch_radius_m;
  auto work = [body = body_, boundary = boundary_, jaw, subgrid] {
    return ComputeJawSubgridCompliance(body->rest_mesh, *boundary, body->settings.material, jaw, subgrid);
  };
  pending_ = std::async(settings_.adopt_steps > 0 ? std::launch::async : std::launch::deferred, work);
  return true;
}

void GraspJaw::Release() {
  if (pending_.valid()) abandoned_.push_back(std::move(pending_));
  // Drop the abandoned workers that have finished (the others are waited for when destroyed).
  std::erase_if(abandoned_, [](const std::future<JawSubgridCompliance>& f) {
    return f.wait_for(std::chrono::seconds(0)) != std::future_status::timeout;
  });
  holding_ = false;
  nodes_.clear();
  weights_.clear();
  computed_.reset();
  adopt_step_ = -1;
}

Eigen::Matrix3d GraspJaw::SubgridAt(long step) {
  if (!holding_ || step < adopt_step_) return Eigen::Matrix3d::Zero();
  if (pending_.valid()) {
    try {
      computed_ = pending_.get();
    } catch (const std::exception& e) {
      failure_ = e.what();
    }
  }
  if (!computed_) return Eigen::Matrix3d::Zero();
  const double ramp =
      std::min(1.0, static_cast<double>(step - adopt_step_ + 1) / static_cast<double>(settings_.ramp_steps));
  return ramp * computed_->subgrid_m_per_N;
}

}  // namespace vesica::physics
