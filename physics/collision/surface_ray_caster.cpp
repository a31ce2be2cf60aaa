#include "physics/collision/surface_ray_caster.h"

#include <BulletCollision/CollisionShapes/btBvhTriangleMeshShape.h>
#include <BulletCollision/CollisionShapes/btOptimizedBvh.h>
#include <BulletCollision/CollisionShapes/btTriangleCallback.h>
#include <BulletCollision/CollisionShapes/btTriangleIndexVertexArray.h>

#include <Eigen/Geometry>
#include <limits>
#include <stdexcept>
#include <string>

namespace vesica::physics {
namespace {

// Margin added to the refit AABB so quantisation never clips a moving triangle.
constexpr double kAabbMarginM = 1e-3;

// Exact segment/triangle crossing (Moller-Trumbore) in double precision.
std::optional<SurfaceHit> IntersectTriangle(const ToolSegment& s, const Eigen::Vector3d& p0, const Eigen::Vector3d& p1,
                                            const Eigen::Vector3d& p2) {
  const Eigen::Vector3d d = s.b - s.a;
  const Eigen::Vector3d e1 = p1 - p0;
  const Eigen::Vector3d e2 = p2 - p0;
  const Eigen::Vector3d h = d.cross(e2);
  const double det = e1.dot(h);
  const double scale = e1.norm() * e2.norm() * d.norm();
  if (std::abs(det) <= 1e-14 * scale) return std::nullopt;  // parallel
  const Eigen::Vector3d t0 = s.a - p0;
  const double u = t0.dot(h) / det;
  if (u < 0.0 || u > 1.0) return std::nullopt;
  const Eigen::Vector3d q = t0.cross(e1);
  const double v = d.dot(q) / det;
  if (v < 0.0 || u + v > 1.0) return std::nullopt;
  const double t = e2.dot(q) / det;
  if (t < 0.0 || t > 1.0) return std::nullopt;
  SurfaceHit hit;
  hit.weights = {1.0 - u - v, u, v};
  hit.point = s.a + t * d;
  hit.normal = e1.cross(e2).normalized();
  hit.distance = t * d.norm();
  hit.from_inside = det < 0.0;  // d points along the normal: leaving the closed surface
  return hit;
}

void CheckSurface(const TriangleMesh& m, const char* where) {
  if (m.num_vertices() == 0 || m.num_triangles() == 0)
    throw std::invalid_argument(std::string(where) + ": surface has no vertices or triangles");
  if (!m.vertices.allFinite()) throw std::invalid_argument(std::string(where) + ": non-finite vertex position");
  for (int f = 0; f < m.num_triangles(); ++f)
    for (int k = 0; k < 3; ++k)
      if (m.triangles(f, k) < 0 || m.triangles(f, k) >= m.num_vertices())
        throw std::invalid_argument(std::string(where) + ": triangle " + std::to_string(f) + " refers to vertex " +
                                    std::to_string(m.triangles(f, k)) + " outside 0.." +
                                    std::to_string(m.num_vertices() - 1));
}

}  // namespace

struct SurfaceRayCaster::Surface {
  TriangleMesh mesh;                // double-precision positions used for exact hits
  std::vector<btScalar> positions;  // Bullet's copy, refreshed before each refit
  std::vector<int> indices;
  std::unique_ptr<btTriangleIndexVertexArray> mesh_interface;
  std::unique_ptr<btBvhTriangleMeshShape> shape;

  void CopyPositions() {
    for (int i = 0; i < mesh.num_vertices(); ++i)
      for (int k = 0; k < 3; ++k) positions[3 * i + k] = static_cast<btScalar>(mesh.vertices(i, k));
  }
  std::pair<btVector3, btVector3> Aabb() const {
    auto [lo, hi] = BoundingBox(mesh.vertices);
    lo.array() -= kAabbMarginM;
    hi.array() += kAabbMarginM;
    return {btVector3(lo.x(), lo.y(), lo.z()), btVector3(hi.x(), hi.y(), hi.z())};
  }
};

SurfaceRayCaster::SurfaceRayCaster() = default;
SurfaceRayCaster::~SurfaceRayCaster() = default;

int SurfaceRayCaster::num_surfaces() const { return static_cast<int>(surfaces_.size()); }

int SurfaceRayCaster::AddSurface(const TriangleMesh& surface) {
  CheckSurface(surface, "SurfaceRayCaster::AddSurface");
  auto s = std::make_unique<Surface>();
  s->mesh = surface;
  s->positions.resize(3 * surface.num_vertices());
  s->CopyPositions();
  s->indices.assign(surface.triangles.data(), surface.triangles.data() + surface.triangles.size());
  s->mesh_interface = std::make_unique<btTriangleIndexVertexArray>(
      surface.num_triangles(), s->indices.data(), 3 * static_cast<int>(sizeof(int)), surface.num_vertices(),
      s->positions.data(), 3 * static_cast<int>(sizeof(btScalar)));
  const auto [lo, hi] = s->Aabb();
  s->shape = std::make_unique<btBvhTriangleMeshShape>(s->mesh_interface.get(), true, lo, hi, true);
  surfaces_.push_back(std::move(s));
  return num_surfaces() - 1;
}

void SurfaceRayCaster::UpdateVertices(int id, const Vertices& vertices) {
  if (id < 0 || id >= num_surfaces())
    throw std::out_of_range("SurfaceRayCaster::UpdateVertices: no surface " + std::to_string(id));
  Surface& s = *surfaces_[id];
  if (vertices.rows() != s.mesh.num_vertices())
    throw std::invalid_argument("SurfaceRayCaster::UpdateVertices: surface " + std::to_string(id) + " has " +
                                std::to_string(s.mesh.num_vertices()) + " vertices, got " +
                                std::to_string(vertices.rows()));
  if (!vertices.allFinite())
    throw std::invalid_argument("SurfaceRayCaster::UpdateVertices: non-finite vertex on surface " + std::to_string(id));
  s.mesh.vertices = vertices;
  s.CopyPositions();
  const auto [lo, hi] = s.Aabb();
  // Refit the BVH only: refitTree would also recompute the shape's local AABB by six support
  // passes over every triangle, which ray casts through performRaycast never read.
  s.shape->getOptimizedBvh()->refit(s.mesh_interface.get(), lo, hi);
}

namespace {
// Collects the nearest exact crossing among the triangles Bullet's BVH reports.
class NearestHitCallback : public btTriangleCallback {
 public:
  NearestHitCallback(const TriangleMesh& mesh, const ToolSegment& seg, int id) : mesh_(mesh), seg_(seg), id_(id) {}
  void processTriangle(btVector3*, int, int triangle) override {
    const auto& t = mesh_.triangles;
    auto hit = IntersectTriangle(seg_, mesh_.vertices.row(t(triangle, 0)).transpose(),
                                 mesh_.vertices.row(t(triangle, 1)).transpose(),
                                 mesh_.vertices.row(t(triangle, 2)).transpose());
    // Ties broken by triangle index so results do not depend on traversal order.
    if (hit &&
        (!best || hit->distance < best->distance || (hit->distance == best->distance && triangle < best->triangle))) {
      hit->surface = id_;
      hit->triangle = triangle;
      best = hit;
    }
  }
  std::optional<SurfaceHit> best;

 private:
  const TriangleMesh& mesh_;
  const ToolSegment& seg_;
  int id_;
};
}  // namespace

std::optional<SurfaceHit> SurfaceRayCaster::FirstHit(int id, const ToolSegment& segment) const {
  if (id < 0 || id >= num_surfaces())
    throw std::out_of_range("SurfaceRayCaster::FirstHit: no surface " + std::to_string(id));
  if (!segment.a.allFinite() || !segment.b.allFinite())
    throw std::invalid_argument("SurfaceRayCaster::FirstHit: non-finite segment end");
  const Surface& s = *surfaces_[id];
  NearestHitCallback callback(s.mesh, segment, id);
  s.shape->performRaycast(&callback, btVector3(segment.a.x(), segment.a.y(), segment.a.z()),
                          btVector3(segment.b.x(), segment.b.y(), segment.b.z()));
  return callback.best;
}

std::optional<SurfaceHit> SurfaceRayCaster::FirstHit(const ToolSegment& segment) const {
  std::optional<SurfaceHit> best;
  for (int id = 0; id < num_surfaces(); ++id) {
    auto hit = FirstHit(id, segment);
    if (hit && (!best || hit->distance < best->distance)) best = hit;
  }
  return best;
}

}  // namespace vesica::physics
