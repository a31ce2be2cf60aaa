#pragma once
// Calot's structures as the scope sees them, by independent projection (tests/app/
// screen_projection.h's pinhole, not the renderer, not the session's own visibility), for the
// scripted sessions' and the rendered critical view's tests (issue 36's image point).

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "app/scenario/scenario.h"
#include "app/session/dissection_session.h"
#include "physics/collision/surface_ray_caster.h"
#include "physics/scene/dissection_model.h"
#include "tests/app/screen_projection.h"

namespace vesica::app::testing {

struct ProjectedSample {
  Eigen::Vector2d pixel;
  double radius_px = 0;
};

// Shortest distance between segments [p0, p1] and [q0, q1] (closest points clamped to both).
inline double SegmentDistance(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& q0,
                              const Eigen::Vector3d& q1) {
  const Eigen::Vector3d d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
  const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r), c = d1.dot(r), b = d1.dot(d2);
  const double denom = a * e - b * b;
  double s = denom > 1e-18 ? std::clamp((b * f - c * e) / denom, 0.0, 1.0) : 0.0;
  double t = (b * s + f) / e;
  if (t < 0.0) {
    t = 0.0, s = std::clamp(-c / a, 0.0, 1.0);
  } else if (t > 1.0) {
    t = 1.0, s = std::clamp((b - c) / a, 0.0, 1.0);
  }
  return (p0 + s * d1 - (q0 + t * d2)).norm();
}

// Whether the sight segment [eye, target] passes through a drawn instrument: its shaft from the
// remote centre to the jaws' hinge (the scenario's shaft radius), the jaws over the last 18 mm
// (1.6 shaft radii wide: app/render/instrument_actors.cpp).
inline bool BehindAnInstrument(const Scenario& scenario, const physics::DissectionModel& model,
                               const DissectionSession& session, const Eigen::Vector3d& eye,
                               const Eigen::Vector3d& target) {
  for (std::size_t i = 0; i < model.instruments.size() && i < scenario.instruments.size(); ++i) {
    const Eigen::Vector3d rc = model.instruments[i].p_RemoteCentre_W;
    const Eigen::Vector3d tip = session.scene().tool_tip(static_cast<int>(i));
    const double r = scenario.instruments[i].shaft_radius_m;
    const Eigen::Vector3d hinge = tip - 0.018 * (tip - rc).normalized();
    if (SegmentDistance(eye, target, rc, hinge) < r || SegmentDistance(eye, target, hinge, tip) < 1.6 * r) return true;
  }
  return false;
}

// Samples every 0.5 mm along the tube, each seen when it projects into the width x height
// picture, the segment from the scope's eye to its near wall crosses neither the liver nor the
// gallbladder as they are now, nor a drawn instrument, and passes no intact fat cell within half a
// cell. Returns each seen sample's pixel and its projected radius (px).
inline std::vector<ProjectedSample> SeenSamples(const Scenario& scenario, const physics::DissectionModel& model,
                                                const DissectionSession& session, int tube, int width = 1280,
                                                int height = 720) {
  physics::SurfaceRayCaster organs;
  organs.UpdateVertices(organs.AddSurface(model.liver->rest_surface), session.scene().liver_positions());
  organs.UpdateVertices(organs.AddSurface(model.gallbladder_boundary.surface),
                        session.scene().gallbladder_surface_positions());
  const ScopeCamera camera = CameraOf(scenario.laparoscope);
  const double focal_px = 0.5 * height / std::tan(0.5 * scenario.laparoscope.view_angle_deg * std::numbers::pi / 180.0);
  const auto& tubes = *session.calot_tubes();
  const auto& fat = *session.calot_fat();
  const double radius_m = tubes.description().tubes[static_cast<std::size_t>(tube)].material.outer_radius_m;
  const double half_cell_m = 0.5 * fat.description().cell_spacing_m;
  std::vector<ProjectedSample> seen;
  for (double s_m = 0; s_m <= tubes.TubeLength_m(tube); s_m += 0.0005) {
    const Eigen::Vector3d p = tubes.PositionAt(tube, s_m);
    const Eigen::Vector2d px = ProjectToPixel(scenario.laparoscope, p, width, height);
    const double depth_m = (p - camera.eye).dot(camera.forward);
    if (depth_m <= 0 || px.x() < 0 || px.x() >= width || px.y() < 0 || px.y() >= height) continue;
    // Up to the tube's near wall, so the tube's own surface does not count.
    const Eigen::Vector3d wall = p - radius_m * (p - camera.eye).normalized();
    if (organs.FirstHit(physics::ToolSegment{camera.eye, wall})) continue;
    if (BehindAnInstrument(scenario, model, session, camera.eye, wall)) continue;
    bool under_fat = false;
    for (std::size_t k = 0; k < fat.cells().size() && !under_fat; ++k) {
      if (fat.cells()[k].state != physics::calot::FatCellState::kIntact) continue;
      const Eigen::Vector3d q = fat.cell_positions_m()[k], d = wall - camera.eye;
      const double u = std::clamp((q - camera.eye).dot(d) / d.squaredNorm(), 0.0, 1.0);
      under_fat = (camera.eye + u * d - q).norm() < half_cell_m;
    }
    if (!under_fat) seen.push_back({px, focal_px * radius_m / depth_m});
  }
  return seen;
}

// The samples of `a` whose projected disc overlaps no disc of `b`'s.
inline std::vector<ProjectedSample> SamplesApart(const std::vector<ProjectedSample>& a,
                                                 const std::vector<ProjectedSample>& b) {
  std::vector<ProjectedSample> apart;
  for (const ProjectedSample& x : a) {
    bool overlaps = false;
    for (const ProjectedSample& y : b) overlaps = overlaps || (x.pixel - y.pixel).norm() < x.radius_px + y.radius_px;
    if (!overlaps) apart.push_back(x);
  }
  return apart;
}

inline int SeparateSamples(const std::vector<ProjectedSample>& a, const std::vector<ProjectedSample>& b) {
  return static_cast<int>(SamplesApart(a, b).size());
}

}  // namespace vesica::app::testing
