#include "fx/burn_map.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "fx/input_checks.h"
#include "physics/mesh/mesh_topology.h"

namespace vesica::fx {

namespace {

Eigen::MatrixX3d Centroids(const Eigen::MatrixX3i& triangles, const physics::Vertices& v) {
  Eigen::MatrixX3d c(triangles.rows(), 3);
  for (Eigen::Index f = 0; f < triangles.rows(); ++f) {
    c.row(f) = (v.row(triangles(f, 0)) + v.row(triangles(f, 1)) + v.row(triangles(f, 2))) / 3.0;
  }
  return c;
}

}  // namespace

BurnMap::BurnMap(std::string name, const physics::TriangleMesh& surface, const BurnParams& params)
    : name_(std::move(name)), params_(params) {
  const std::string owner = "BurnMap '" + name_ + "'";
  CheckPositive(owner, "rate_per_s", params.rate_per_s);
  CheckPositive(owner, "spread_radius_m", params.spread_radius_m);
  CheckPositive(owner, "damage_threshold", params.damage_threshold);
  if (params.damage_threshold > 1) {
    throw std::invalid_argument(owner + ": damage_threshold must be <= 1");
  }
  if (!surface.vertices.allFinite()) {
    throw std::invalid_argument(owner + ": surface has non-finite vertices");
  }
  const int nv = surface.num_vertices();
  for (int f = 0; f < surface.num_triangles(); ++f) {
    for (int k = 0; k < 3; ++k) {
      CheckIndex(owner + ": triangle " + std::to_string(f), "vertex", surface.triangles(f, k), nv);
    }
  }
  triangles_ = surface.triangles;
  centroids_ = Centroids(triangles_, surface.vertices);
  const int nf = surface.num_triangles();
  rest_area_m2_.resize(static_cast<size_t>(nf));
  edge_neighbours_.resize(static_cast<size_t>(nf));
  const physics::Triangles adjacency = physics::TriangleAdjacency(surface);
  for (int f = 0; f < nf; ++f) {
    rest_area_m2_[static_cast<size_t>(f)] = physics::TriangleArea(surface, f);
    for (int k = 0; k < 3; ++k) {
      if (adjacency(f, k) >= 0) edge_neighbours_[static_cast<size_t>(f)].push_back(adjacency(f, k));
    }
  }
  level_.assign(static_cast<size_t>(nf), 0.0);
  level_float_.assign(static_cast<size_t>(nf), 0.0f);
  damaged_.assign(static_cast<size_t>(nf), 0);
  visit_stamp_.assign(static_cast<size_t>(nf), 0);
}

void BurnMap::UpdateGeometry(const physics::Vertices& vertices) {
  const std::string owner = "BurnMap '" + name_ + "'";
  const int expected = triangles_.size() == 0 ? static_cast<int>(vertices.rows()) : triangles_.maxCoeff() + 1;
  if (vertices.rows() < expected) {
    throw std::invalid_argument(owner + ": UpdateGeometry got " + std::to_string(vertices.rows()) +
                                " vertices, the surface uses " + std::to_string(expected));
  }
  if (!vertices.allFinite()) throw std::invalid_argument(owner + ": UpdateGeometry got non-finite vertices");
  centroids_ = Centroids(triangles_, vertices);
}

void BurnMap::Burn(int element, double dt_s, double time_s) {
  const std::string owner = "BurnMap '" + name_ + "'";
  CheckIndex(owner, "element", element, num_elements());
  CheckNonNegative(owner, "dt_s", dt_s);
  if (!std::isfinite(time_s)) throw std::invalid_argument(owner + ": time_s is not finite");

  // Breadth-first over edge neighbours, stopping where the fall-off reaches zero.
  ++stamp_;
  queue_.clear();
  queue_.push_back(element);
  visit_stamp_[static_cast<size_t>(element)] = stamp_;
  const Eigen::Vector3d origin = centroids_.row(element).transpose();
  for (size_t head = 0; head < queue_.size(); ++head) {
    const int f = queue_[head];
    const auto fi = static_cast<size_t>(f);
    const double d = (centroids_.row(f).transpose() - origin).norm();
    const double falloff = 1.0 - d / params_.spread_radius_m;
    if (f != element && falloff <= 0) continue;  // out of reach: neither burn nor walk past it
    level_[fi] = std::min(1.0, level_[fi] + params_.rate_per_s * dt_s * std::max(falloff, 0.0));
    level_float_[fi] = static_cast<float>(level_[fi]);
    if (params_.records_damage && !damaged_[fi] && level_[fi] > params_.damage_threshold) {
      damaged_[fi] = 1;
      damage_events_.push_back({f, time_s, level_[fi]});
      damaged_area_m2_ += rest_area_m2_[fi];
    }
    for (int n : edge_neighbours_[fi]) {
      if (visit_stamp_[static_cast<size_t>(n)] == stamp_) continue;
      visit_stamp_[static_cast<size_t>(n)] = stamp_;
      queue_.push_back(n);
    }
  }
}

}  // namespace vesica::fx
