#include "app/render/render_frame.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace vesica::app {

namespace {

[[noreturn]] void Fail(const std::string& message) { throw std::invalid_argument("RenderFrame." + message); }

// Rows must be `expected`, or 0 where "empty" means rest.
void CheckRows(const char* field, const physics::Vertices& v, int expected, bool empty_ok) {
  if (empty_ok && v.rows() == 0) return;
  if (v.rows() != expected)
    Fail(std::string(field) + ": " + std::to_string(v.rows()) + " rows, the scene has " + std::to_string(expected) +
         (empty_ok ? " (or 0 for rest)" : ""));
  for (Eigen::Index i = 0; i < v.rows(); ++i)
    if (!v.row(i).allFinite()) Fail(std::string(field) + ": row " + std::to_string(i) + " is not finite");
}

void CheckPerTriangle(const char* field, const std::vector<float>& values, std::size_t expected) {
  if (values.empty()) return;
  if (values.size() != expected)
    Fail(std::string(field) + ": " + std::to_string(values.size()) + " values, expected " + std::to_string(expected) +
         " (one per triangle) or 0");
  for (std::size_t i = 0; i < values.size(); ++i)
    if (!std::isfinite(values[i])) Fail(std::string(field) + "[" + std::to_string(i) + "] is not finite");
}

}  // namespace

void ValidateRenderFrame(const RenderFrame& frame, const RenderFrameSizes& sizes) {
  CheckRows("liver_vertices", frame.liver_vertices, sizes.liver_vertices, true);
  CheckRows("gallbladder_vertices", frame.gallbladder_vertices, sizes.gallbladder_vertices, true);
  CheckPerTriangle("liver_burn", frame.liver_burn, static_cast<std::size_t>(sizes.liver_triangles));
  CheckPerTriangle("gallbladder_burn", frame.gallbladder_burn, static_cast<std::size_t>(sizes.gallbladder_triangles));

  const auto n_membrane = static_cast<int>(frame.membrane_vertices.rows());
  CheckRows("membrane_vertices", frame.membrane_vertices, n_membrane, false);
  const auto& tris = frame.membrane_triangles;
  for (Eigen::Index f = 0; f < tris.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      if (tris(f, k) < 0 || tris(f, k) >= n_membrane)
        Fail("membrane_triangles: row " + std::to_string(f) + " uses vertex " + std::to_string(tris(f, k)) +
             ", membrane_vertices has " + std::to_string(n_membrane) + " rows");
  CheckPerTriangle("membrane_opacity", frame.membrane_opacity, static_cast<std::size_t>(tris.rows()));
  CheckPerTriangle("membrane_burn", frame.membrane_burn, static_cast<std::size_t>(tris.rows()));

  for (std::size_t i = 0; i < frame.smoke.size(); ++i) {
    const auto& s = frame.smoke[i];
    const std::string at = "smoke[" + std::to_string(i) + "]";
    if (!s.p_W.allFinite()) Fail(at + ".p_W is not finite");
    if (!std::isfinite(s.size_m) || s.size_m < 0) Fail(at + ".size_m must be finite and >= 0, got " + std::to_string(s.size_m));
    if (!std::isfinite(s.alpha)) Fail(at + ".alpha is not finite");
  }

  if (!frame.instruments.empty() && frame.instruments.size() != sizes.instruments)
    Fail("instruments: " + std::to_string(frame.instruments.size()) + " entries, the scenario has " +
         std::to_string(sizes.instruments) + " (or 0 to keep the poses)");
  for (std::size_t i = 0; i < frame.instruments.size(); ++i) {
    const auto& p = frame.instruments[i].pose;
    for (double v : {p.yaw_rad, p.pitch_rad, p.roll_rad, p.insertion_m, p.jaw_angle_rad})
      if (!std::isfinite(v)) Fail("instruments[" + std::to_string(i) + "].pose is not finite");
    const double past = frame.instruments[i].past_contact_m;
    if (!std::isfinite(past) || past < 0 || past > std::max(p.insertion_m, 0.0))
      Fail("instruments[" + std::to_string(i) + "].past_contact_m: " + std::to_string(past) +
           " is not in [0, insertion_m]");
  }
}

}  // namespace vesica::app
