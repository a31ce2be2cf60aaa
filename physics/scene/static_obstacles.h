#pragma once
// Organs around the gallbladder that do not move in the simulation but hold it up (issue 30: a
// freed gallbladder rests on the organs below it): tubes (bowel, ducts) as chains of capsules
// along their centreline's points, and axis-aligned ellipsoids (stomach, omentum), each with an
// analytic signed distance. The scenario's solid [[context_organs]] become these.

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

namespace vesica::physics {

/// A tube: the union of capsules of radius_m around consecutive centreline points.
struct ObstacleTube {
  std::string name;                           ///< for error messages
  std::vector<Eigen::Vector3d> centreline_W;  ///< >= 2 points, metres
  double radius_m = 0;                        ///< > 0
};

struct ObstacleEllipsoid {
  std::string name;
  Eigen::Vector3d centre_W = Eigen::Vector3d::Zero();
  Eigen::Vector3d semi_axes_m = Eigen::Vector3d::Zero();  ///< along x, y, z, each > 0
};

struct StaticObstacles {
  std::vector<ObstacleTube> tubes;
  std::vector<ObstacleEllipsoid> ellipsoids;
  bool empty() const { return tubes.empty() && ellipsoids.empty(); }
};

struct ObstacleProximity {
  Eigen::Vector3d p_Surface_W = Eigen::Vector3d::Zero();  ///< nearest surface point
  Eigen::Vector3d normal_W = Eigen::Vector3d::Zero();     ///< unit, out of the obstacle
  double signed_distance_m = 0;                           ///< negative inside
};

/// Throws std::invalid_argument naming the obstacle when a tube has < 2 points, a non-positive
/// radius, two coincident consecutive points or a non-finite value, or an ellipsoid has a
/// non-positive or non-finite semi-axis.
void CheckStaticObstacles(const StaticObstacles& obstacles);

/// Signed distance of p_W to one tube (negative inside), its nearest surface point and normal.
ObstacleProximity TubeProximity(const ObstacleTube& tube, const Eigen::Vector3d& p_W);

/// The obstacle surface nearest to p_W among those whose signed distance lies in
/// (-max_depth_m, within_m]: a point deeper than max_depth_m inside an obstacle is not pushed (it
/// could only be pushed out of the far side of a thin one), nor is one farther than within_m.
std::optional<ObstacleProximity> NearestObstacle(const StaticObstacles& obstacles, const Eigen::Vector3d& p_W,
                                                 double within_m, double max_depth_m);

}  // namespace vesica::physics
