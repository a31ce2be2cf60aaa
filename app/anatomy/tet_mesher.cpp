#include "app/anatomy/tet_mesher.h"

#include <tetgen.h>

#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <vector>

namespace vesica::app::anatomy {

using physics::TetrahedralMesh;
using physics::TriangleMesh;

TetrahedralMesh Tetrahedralise(const TriangleMesh& surface, const std::string& switches) {
  tetgenio in;  // tetgenio's destructor releases these arrays with delete[]
  tetgenio out;
  in.firstnumber = 0;
  in.numberofpoints = surface.num_vertices();
  in.pointlist = new REAL[3 * in.numberofpoints];
  for (int i = 0; i < surface.num_vertices(); ++i) {
    for (int k = 0; k < 3; ++k) in.pointlist[3 * i + k] = surface.vertices(i, k);
  }
  in.numberoffacets = surface.num_triangles();
  in.facetlist = new tetgenio::facet[in.numberoffacets];
  for (int f = 0; f < surface.num_triangles(); ++f) {
    tetgenio::facet& facet = in.facetlist[f];
    facet.numberofpolygons = 1;
    facet.polygonlist = new tetgenio::polygon[1];
    facet.numberofholes = 0;
    facet.holelist = nullptr;
    tetgenio::polygon& polygon = facet.polygonlist[0];
    polygon.numberofvertices = 3;
    polygon.vertexlist = new int[3];
    for (int k = 0; k < 3; ++k) polygon.vertexlist[k] = surface.triangles(f, k);
  }

  std::vector<char> argument(switches.begin(), switches.end());
  argument.push_back('\0');
  try {
    tetrahedralize(argument.data(), &in, &out);
  } catch (int code) {  // TetGen built as a library reports failure by throwing its exit code
    throw std::runtime_error("TetGen '" + switches + "' failed with code " + std::to_string(code));
  }
  if (out.numberofcorners != 4 || out.numberoftetrahedra == 0) {
    throw std::runtime_error("TetGen '" + switches + "' produced no linear tetrahedra");
  }

  TetrahedralMesh mesh;
  mesh.vertices.resize(out.numberofpoints, 3);
  for (int i = 0; i < out.numberofpoints; ++i) {
    for (int k = 0; k < 3; ++k) mesh.vertices(i, k) = out.pointlist[3 * i + k];
  }
  mesh.tets.resize(out.numberoftetrahedra, 4);
  for (int t = 0; t < out.numberoftetrahedra; ++t) {
    for (int k = 0; k < 4; ++k) mesh.tets(t, k) = out.tetrahedronlist[4 * t + k];
    if (physics::SignedTetVolume(mesh, t) < 0) std::swap(mesh.tets(t, 2), mesh.tets(t, 3));
  }
  return mesh;
}

namespace {

std::string QualitySwitches(const TetQualityRequest& q, double max_volume_m3) {
  char buffer[128];
  std::snprintf(buffer, sizeof buffer, "pq%.3g/%.3ga%.4eO%d/7%sQ", q.max_radius_edge, q.min_dihedral_deg, max_volume_m3,
                q.optimisation_level, q.keep_surface ? "Y" : "");
  return buffer;
}

}  // namespace

SizedTetMesh TetrahedraliseToNodeCount(const TriangleMesh& surface, int target_nodes,
                                       const TetQualityRequest& quality) {
  if (target_nodes <= surface.num_vertices()) {
    throw std::invalid_argument("TetrahedraliseToNodeCount: target " + std::to_string(target_nodes) +
                                " is not above the surface's " + std::to_string(surface.num_vertices()) + " vertices");
  }
  const double volume = physics::EnclosedVolume(surface);
  // Node count falls as the volume bound grows; bisect on its logarithm.
  double log_small = std::log(volume * 1e-6);
  double log_large = std::log(volume);
  SizedTetMesh best;
  int best_error = -1;
  for (int step = 0; step < 40; ++step) {
    const double log_bound = 0.5 * (log_small + log_large);
    const std::string switches = QualitySwitches(quality, std::exp(log_bound));
    TetrahedralMesh mesh = Tetrahedralise(surface, switches);
    const int nodes = mesh.num_vertices();
    const int error = std::abs(nodes - target_nodes);
    if (best_error < 0 || error < best_error) {
      best_error = error;
      best = {std::move(mesh), switches};
    }
    if (error == 0) break;
    (nodes > target_nodes ? log_small : log_large) = log_bound;
  }
  return best;
}

}  // namespace vesica::app::anatomy
