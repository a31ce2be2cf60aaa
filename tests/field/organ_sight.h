#pragma once
// What the laparoscope sees of the scene, by rays from the scope's tip at the deformed organs'
// triangles (brute force, app/anatomy/surface_distance.h): no VTK, no Bullet. Shared by the
// surgeon's-view tests.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>
#include <limits>

#include "app/anatomy/surface_distance.h"
#include "physics/scene/dissection_scene.h"

namespace vesica::app::testing {

/// The liver's surface as the scene has it now.
inline physics::TriangleMesh LiverNow(const physics::DissectionScene& scene) {
  physics::TriangleMesh m = scene.model().liver->rest_surface;
  m.vertices = scene.liver_positions();
  return m;
}

/// The gallbladder's boundary as the scene has it now.
inline physics::TriangleMesh GallbladderNow(const physics::DissectionScene& scene) {
  physics::TriangleMesh m = scene.model().gallbladder_boundary.surface;
  m.vertices = scene.gallbladder_surface_positions();
  return m;
}

/// True when the segment from `eye` to `point` crosses neither surface, up to `tolerance_m`
/// short of the point (things that touch the organs, the membrane's corners, a tool tip pressing).
inline bool InSight(const Eigen::Vector3d& eye, const Eigen::Vector3d& point, const physics::TriangleMesh& liver,
                    const physics::TriangleMesh& gallbladder, double tolerance_m) {
  const Eigen::Vector3d to = point - eye;
  const Eigen::Vector3d dir = to.normalized();
  const double inf = std::numeric_limits<double>::infinity();
  const double nearest = std::min(anatomy::FirstRayHit(liver, eye, dir).value_or(inf),
                                  anatomy::FirstRayHit(gallbladder, eye, dir).value_or(inf));
  return nearest > to.norm() - tolerance_m;
}

struct MembraneSight {
  double area_m2 = 0;
  double visible = 0;      ///< fraction of the area whose centroid the scope sees
  double not_edge_on = 0;  ///< fraction whose normal is within 78 degrees of the line of sight
};

/// The still-attached membrane (both springs of a triangle alive) as seen from `eye`.
inline MembraneSight SeeMembrane(const physics::DissectionScene& scene, const Eigen::Vector3d& eye) {
  const physics::TriangleMesh liver = LiverNow(scene), gallbladder = GallbladderNow(scene);
  const physics::Vertices points = scene.membrane_points();
  const physics::TissueMembrane& membrane = scene.tissue().membrane;
  MembraneSight sight;
  for (Eigen::Index f = 0; f < membrane.triangles.rows(); ++f) {
    if (!scene.tissue().springs[static_cast<size_t>(membrane.springs(f, 0))].alive ||
        !scene.tissue().springs[static_cast<size_t>(membrane.springs(f, 1))].alive)
      continue;
    const Eigen::Vector3d a = points.row(membrane.triangles(f, 0)), b = points.row(membrane.triangles(f, 1)),
                          c = points.row(membrane.triangles(f, 2));
    const Eigen::Vector3d n = (b - a).cross(c - a);
    const double area = 0.5 * n.norm();
    if (!(area > 0)) continue;
    const Eigen::Vector3d centroid = (a + b + c) / 3.0;
    sight.area_m2 += area;
    if (InSight(eye, centroid, liver, gallbladder, 0.0005)) sight.visible += area;
    if (std::abs(n.normalized().dot((centroid - eye).normalized())) > 0.2) sight.not_edge_on += area;
  }
  if (sight.area_m2 > 0) {
    sight.visible /= sight.area_m2;
    sight.not_edge_on /= sight.area_m2;
  }
  return sight;
}

}  // namespace vesica::app::testing
