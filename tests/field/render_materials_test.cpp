// The picture's materials and depth cues (issue 30, "Picture"): the instruments' shadows fall
// where an independent ray from the scope's light past the shaft meets the liver; the grasper's
// fenestrated jaws show the tissue through their windows; a burn fades smoothly into the tissue
// around it (no step at a triangle's edge); the physically based liver is dark red-brown with a
// wet highlight. Geometry here is the test's own (rays against the rest meshes, the pinhole of
// screen_projection.h), not VTK's.

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <optional>

#include "../app/offscreen_render.h"
#include "../app/screen_projection.h"
#include "app/render/grasper_jaw.h"
#include "app/render/instrument_actors.h"
#include "app/render/laparoscope_view.h"
#include "app/render/render_colours.h"
#include "app/render/scene_meshes.h"
#include "app/render/scope_light.h"
#include "app/scenario/scenario_loader.h"
#include "cie_lab.h"
#include "physics/mesh/mesh_topology.h"

namespace vesica::app {
namespace {

using testing::OffscreenRender;
using testing::Picture;
using testing::Rgb;

constexpr int kWidth = 960, kHeight = 540;

testing::Lab LabOf(Rgb c) { return testing::SrgbToLab(c.r, c.g, c.b); }

// Mean L*a*b* of the (2h+1)^2 pixels around (col, row).
testing::Lab MeanLab(const Picture& pic, double col, double row, int h) {
  double L = 0, a = 0, b = 0;
  int n = 0;
  for (int dr = -h; dr <= h; ++dr)
    for (int dc = -h; dc <= h; ++dc) {
      const int c = static_cast<int>(std::lround(col)) + dc, r = static_cast<int>(std::lround(row)) + dr;
      if (!pic.contains(c, r)) continue;
      const testing::Lab lab = LabOf(pic.at(c, r));
      L += lab.L, a += lab.a, b += lab.b, ++n;
    }
  return {L / n, a / n, b / n};
}

// Möller-Trumbore: the ray's parameter at its first hit on the mesh, if any.
std::optional<double> FirstHit(const physics::TriangleMesh& mesh, const Eigen::Vector3d& origin,
                               const Eigen::Vector3d& direction) {
  std::optional<double> best;
  for (int f = 0; f < mesh.num_triangles(); ++f) {
    const Eigen::Vector3d p0 = mesh.vertices.row(mesh.triangles(f, 0)).transpose();
    const Eigen::Vector3d e1 = mesh.vertices.row(mesh.triangles(f, 1)).transpose() - p0;
    const Eigen::Vector3d e2 = mesh.vertices.row(mesh.triangles(f, 2)).transpose() - p0;
    const Eigen::Vector3d q = direction.cross(e2);
    const double det = e1.dot(q);
    if (std::abs(det) < 1e-14) continue;
    const Eigen::Vector3d s = origin - p0;
    const double u = s.dot(q) / det;
    if (u < 0 || u > 1) continue;
    const Eigen::Vector3d r = s.cross(e1);
    const double v = direction.dot(r) / det;
    if (v < 0 || u + v > 1) continue;
    const double t = e2.dot(r) / det;
    if (t > 1e-9 && (!best || t < *best)) best = t;
  }
  return best;
}

double SegmentDistance(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const Eigen::Vector3d ab = b - a;
  const double t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  return (a + t * ab - p).norm();
}

// Distance from the segment [o, o + d*len] (d unit) to the segment [a, b], by sampling (test-side).
double RayToSegment(const Eigen::Vector3d& o, const Eigen::Vector3d& d, double len, const Eigen::Vector3d& a,
                    const Eigen::Vector3d& b) {
  double best = 1e9;
  for (int i = 0; i <= 400; ++i) best = std::min(best, SegmentDistance(o + (len * i / 400.0) * d, a, b));
  return best;
}

class RenderMaterialsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    // The overview layout: the scope looks down on the liver, so the hook's shadow and a burn fall
    // on open liver surface the test's rays can follow.
    scenario_ = LoadScenario(std::filesystem::path(VESICA_SOURCE_DIR) / "data/scenarios/cholecystectomy-overview.toml");
    scenario_.context_organs.clear();  // only the simulated organs: the test's rays know them
    scenario_.abdominal_wall.opacity = 0;
    meshes_ = LoadSceneMeshes(scenario_);
    gallbladder_ = physics::ExtractBoundary(meshes_.gallbladder).surface;
    const LaparoscopeConfig& scope = scenario_.laparoscope;
    forward_ = (scope.look_at_m - scope.position_m).normalized();
    eye_ = scope.position_m + scope.insertion_m * forward_;
    up_ = (Eigen::Vector3d::UnitY() - forward_.y() * forward_).normalized();
    right_ = up_.cross(forward_);
    for (std::size_t i = 0; i < scenario_.instruments.size(); ++i)
      (scenario_.instruments[i].kind == InstrumentKind::kGrasper ? grasper_ : hook_) = i;
  }

  Eigen::Vector2d Pixel(const Eigen::Vector3d& p) const {
    return testing::ProjectToPixel(scenario_.laparoscope, p, kWidth, kHeight);
  }
  Eigen::Vector3d Centre(std::size_t i) const { return scenario_.trocar(scenario_.instruments[i].trocar).position_m; }
  Eigen::Vector3d Reference(std::size_t i) const { return (scenario_.laparoscope.look_at_m - Centre(i)).normalized(); }
  physics::InstrumentPose Aim(std::size_t i, const Eigen::Vector3d& tip) const {
    return physics::AimAt(Centre(i), tip, (tip - Centre(i)).norm(), Reference(i));
  }
  // Parked: the tip 1 cm past the port, out of the scope's view.
  physics::InstrumentPose Parked(std::size_t i) const { return Aim(i, Centre(i) + 0.01 * Reference(i)); }

  // Whether p (on the liver) is what the camera sees along its line of sight (nothing simulated
  // in front of it).
  bool SeenFromTheScope(const Eigen::Vector3d& p) const {
    const Eigen::Vector3d d = (p - eye_).normalized();
    const double dist = (p - eye_).norm();
    const auto liver = FirstHit(meshes_.liver, eye_, d);
    const auto gb = FirstHit(gallbladder_, eye_, d);
    return liver && std::abs(*liver - dist) < 1e-4 && (!gb || *gb > dist);
  }

  // Liver vertices seen from the scope, well inside the picture, at least clear_px from where the
  // gallbladder projects and facing the scope (|cos| >= min_facing), nearest the picture's centre first.
  std::vector<Eigen::Vector3d> VisibleLiverPoints(int margin_px, double clear_px = 0, double min_facing = 0) const {
    std::vector<Eigen::Vector2d> gallbladder_px;
    for (int v = 0; v < gallbladder_.num_vertices(); ++v)
      gallbladder_px.push_back(Pixel(gallbladder_.vertices.row(v).transpose()));
    std::vector<std::pair<double, Eigen::Vector3d>> found;
    for (int v = 0; v < meshes_.liver.num_vertices(); ++v) {
      const Eigen::Vector3d p = meshes_.liver.vertices.row(v).transpose();
      const Eigen::Vector2d px = Pixel(p);
      if (px.x() < margin_px || px.y() < margin_px || px.x() > kWidth - margin_px || px.y() > kHeight - margin_px)
        continue;
      // Facing the scope (the mesh's vertex normal, either orientation).
      Eigen::Vector3d normal = Eigen::Vector3d::Zero();
      for (int f = 0; f < meshes_.liver.num_triangles(); ++f)
        for (int k = 0; k < 3; ++k)
          if (meshes_.liver.triangles(f, k) == v) {
            const auto& m = meshes_.liver;
            const Eigen::Vector3d a = m.vertices.row(m.triangles(f, 0)).transpose();
            normal += (m.vertices.row(m.triangles(f, 1)).transpose() - a)
                          .cross(m.vertices.row(m.triangles(f, 2)).transpose() - a);
          }
      if (std::abs(normal.normalized().dot((eye_ - p).normalized())) < min_facing) continue;
      bool clear = true;
      for (const Eigen::Vector2d& g : gallbladder_px) clear &= (g - px).norm() >= clear_px;
      if (!clear) continue;
      // The vertex itself may be a silhouette: step a hair towards the camera and look again.
      if (!SeenFromTheScope(p + 1e-5 * (eye_ - p).normalized())) continue;
      found.emplace_back((px - Eigen::Vector2d(kWidth / 2.0, kHeight / 2.0)).norm(), p);
    }
    std::sort(found.begin(), found.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    std::vector<Eigen::Vector3d> out;
    for (const auto& f : found) out.push_back(f.second);
    return out;
  }

  Scenario scenario_;
  SceneMeshes meshes_;
  physics::TriangleMesh gallbladder_;
  Eigen::Vector3d forward_, eye_, up_, right_;
  std::size_t grasper_ = 0, hook_ = 1;
};

// The hook held 8 mm above the liver: each point of its shaft, cast from the scope's light onto
// the liver, is darker with the shadows on than off (where the scope sees that point, not the
// instrument itself); the rest of the picture is as it was.
TEST_F(RenderMaterialsTest, TheHookShadowFallsWhereTheLightProjectsItsShaft) {
  const std::vector<Eigen::Vector3d> candidates = VisibleLiverPoints(150, 150, 0.6);
  ASSERT_FALSE(candidates.empty());
  const Eigen::Vector3d target = candidates.front();
  const Eigen::Vector3d tip = target + 0.008 * (eye_ - target).normalized();
  LaparoscopeView view(scenario_, meshes_);
  view.SetInstrumentPose(grasper_, Parked(grasper_));
  const physics::InstrumentPose pose = Aim(hook_, tip);
  view.SetInstrumentPose(hook_, pose);
  OffscreenRender render(kWidth, kHeight);
  view.ShowInstrumentShadows(false);
  const Picture off = render.Render(view);
  render.SaveLast("field_shadow_off.png");
  view.ShowInstrumentShadows(true);
  const Picture on = render.Render(view);
  render.SaveLast("field_shadow_on.png");

  // The hook as drawn: its shaft from far outside to the stem's start, then the stem to the tip.
  const InstrumentConfig& hook = scenario_.instruments[hook_];
  const Eigen::Vector3d d = (tip - Centre(hook_)).normalized();
  const Eigen::Vector3d stem_start = tip - kHookStem_m * d;
  const Eigen::Vector3d light = ScopeLightPosition(eye_, right_, up_);
  int visible = 0, darker = 0, hits = 0, inside = 0, seen = 0;
  for (double back_m = 0.0; back_m <= 0.10; back_m += 0.002) {
    const Eigen::Vector3d q = tip - back_m * d;
    const auto hit = FirstHit(meshes_.liver, light, (q - light).normalized());
    if (!hit) continue;
    ++hits;
    const Eigen::Vector3d s = light + *hit * (q - light).normalized();
    const Eigen::Vector2d px = Pixel(s);
    if (px.x() < 4 || px.y() < 4 || px.x() > kWidth - 4 || px.y() > kHeight - 4) continue;
    ++inside;
    if (!SeenFromTheScope(s - 1e-5 * (s - eye_).normalized())) continue;
    ++seen;
    // Hidden behind the instrument itself (1 mm margin for its silhouette's antialiasing).
    const Eigen::Vector3d sight = (s - eye_).normalized();
    const double len = (s - eye_).norm();
    std::printf("  %2.0f mm back: sight passes the shaft at %.1f mm, the stem at %.1f mm; shadow at (%4.0f, %4.0f)\n",
                1000 * back_m, 1000 * RayToSegment(eye_, sight, len, Centre(hook_) - 0.1 * d, stem_start),
                1000 * RayToSegment(eye_, sight, len, stem_start, tip), px.x(), px.y());
    if (RayToSegment(eye_, sight, len, Centre(hook_) - 0.1 * d, stem_start) < hook.shaft_radius_m + 0.001) continue;
    if (RayToSegment(eye_, sight, len, stem_start, tip) < 0.6 * hook.shaft_radius_m + 0.001) continue;
    ++visible;
    const double dL = MeanLab(off, px.x(), px.y(), 1).L - MeanLab(on, px.x(), px.y(), 1).L;
    darker += dL > 5.0;
    std::printf("shadow of the shaft %2.0f mm behind the tip at (%4.0f, %4.0f): L* %.1f without, %.1f with\n",
                1000 * back_m, px.x(), px.y(), MeanLab(off, px.x(), px.y(), 1).L, MeanLab(on, px.x(), px.y(), 1).L);
  }
  int changed = 0, min_col = kWidth, max_col = 0, min_row = kHeight, max_row = 0;
  for (int row = 0; row < kHeight; ++row)
    for (int col = 0; col < kWidth; ++col)
      if (testing::DeltaE76(LabOf(off.at(col, row)), LabOf(on.at(col, row))) > 3) {
        ++changed;
        min_col = std::min(min_col, col), max_col = std::max(max_col, col);
        min_row = std::min(min_row, row), max_row = std::max(max_row, row);
      }
  std::printf("changed pixels within columns %d..%d, rows %d..%d; the tip at (%.0f, %.0f)\n", min_col, max_col, min_row,
              max_row, Pixel(tip).x(), Pixel(tip).y());
  std::printf(
      "shadow: %d rays hit the liver, %d in the picture, %d seen, %d beside the hook; %d of these darker by "
      "> 5 L*; %.2f %% of the picture changed\n",
      hits, inside, seen, visible, darker, 100.0 * changed / (kWidth * kHeight));
  ASSERT_GE(visible, 4) << "the shadow should be in view beside the shaft";
  EXPECT_GE(darker, 0.75 * visible);
  EXPECT_LT(changed, 0.05 * kWidth * kHeight) << "a shadow, not a darker picture";
}

// The closed grasper held over the liver with the backs of its jaws towards the scope: through
// the windows the tissue shows as it does without the grasper; on the blade beside each window,
// steel.
TEST_F(RenderMaterialsTest, TheGrasperJawsShowTheTissueThroughTheirWindows) {
  const std::vector<Eigen::Vector3d> candidates = VisibleLiverPoints(150, 120, 0.6);
  ASSERT_FALSE(candidates.empty());
  const Eigen::Vector3d target = candidates.front();
  const Eigen::Vector3d tip = target + 0.02 * (eye_ - target).normalized();
  const Eigen::Vector3d d = (tip - Centre(grasper_)).normalized();
  const GrasperJawShape jaw = GrasperJawFor(scenario_.instruments[grasper_].shaft_radius_m);
  const Eigen::Vector3d hinge = tip - jaw.length_m * d;
  // Roll so that the jaws' backs (the opening plane's normal... the "side" axis) face the scope.
  physics::InstrumentPose pose = Aim(grasper_, tip);
  Eigen::Vector3d base = d.cross(Eigen::Vector3d::UnitZ()).normalized();
  const Eigen::Vector3d towards = eye_ - hinge;
  const Eigen::Vector3d wanted = (towards - towards.dot(d) * d).normalized();
  pose.roll_rad = std::atan2(d.dot(base.cross(wanted)), base.dot(wanted));
  pose.jaw_angle_rad = 0;

  LaparoscopeView view(scenario_, meshes_);
  view.ShowInstrumentShadows(false);  // compare the tissue itself, not its shade
  view.SetInstrumentPose(hook_, Parked(hook_));
  view.SetInstrumentPose(grasper_, Parked(grasper_));
  OffscreenRender render(kWidth, kHeight);
  const Picture bare = render.Render(view);
  view.SetInstrumentPose(grasper_, pose);
  const Picture held = render.Render(view);
  render.SaveLast("field_grasper_window.png");

  const Eigen::Vector3d across = d.cross(wanted).normalized();  // the blade's width
  const Eigen::Vector3d window_centre = hinge + 0.5 * jaw.length_m * d;
  const double bar_m = 0.25 * (jaw.width_m + jaw.window_width_m);  // middle of the steel beside the window
  int windows_clear = 0, bars_steel = 0, samples = 0;
  for (const double along : {-0.25, 0.0, 0.25}) {
    const Eigen::Vector3d c = window_centre + along * jaw.window_length_m * d;
    ASSERT_TRUE(InGrasperJawWindow(jaw, 0.5 * jaw.length_m + along * jaw.window_length_m, 0));
    const Eigen::Vector2d w = Pixel(c);
    const double through = testing::DeltaE76(MeanLab(bare, w.x(), w.y(), 1), MeanLab(held, w.x(), w.y(), 1));
    double bar = 1e9;
    for (const double sign : {-1.0, 1.0}) {
      const Eigen::Vector2d b = Pixel(c + sign * bar_m * across);
      bar = std::min(bar, testing::DeltaE76(MeanLab(bare, b.x(), b.y(), 0), MeanLab(held, b.x(), b.y(), 0)));
    }
    std::printf("window at (%4.0f, %4.0f): dE %.1f to the bare tissue; the blade beside it: dE %.1f\n", w.x(), w.y(),
                through, bar);
    ++samples;
    windows_clear += through < 8.0;
    bars_steel += bar > 15.0;
  }
  const double window_px = (Pixel(window_centre + 0.5 * jaw.window_width_m * across) - Pixel(window_centre)).norm();
  std::printf("window half-width on screen: %.1f px\n", window_px);
  ASSERT_GT(window_px, 3.0) << "the window should be several pixels wide at this distance";
  EXPECT_EQ(windows_clear, samples) << "tissue seen through the fenestrations";
  EXPECT_EQ(bars_steel, samples) << "steel beside them";
}

// A coagulated patch of the liver (the ramp's whitened level on the triangles within 12 mm of a
// point): along lines from its centre outwards, the change of L* against the unburnt picture
// falls to zero without a step: no two samples 2 px apart differ by more than a fifth of the
// patch's contrast. Drawn per triangle, the patch's edge is a step of all its contrast.
TEST_F(RenderMaterialsTest, ABurnFadesIntoTheTissueWithoutAStepAtTriangleEdges) {
  const std::vector<Eigen::Vector3d> candidates = VisibleLiverPoints(150, 120, 0.6);
  ASSERT_FALSE(candidates.empty());
  const Eigen::Vector3d centre = candidates.front();
  LaparoscopeView view(scenario_, meshes_);
  view.ShowInstrumentShadows(false);
  view.SetInstrumentPose(hook_, Parked(hook_));
  view.SetInstrumentPose(grasper_, Parked(grasper_));
  OffscreenRender render(kWidth, kHeight);
  const Picture unburnt = render.Render(view);
  RenderFrame frame;
  const physics::TriangleMesh& liver = meshes_.liver;
  frame.liver_burn.assign(static_cast<std::size_t>(liver.num_triangles()), 0.0f);
  int burnt = 0;
  for (int f = 0; f < liver.num_triangles(); ++f) {
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for (int k = 0; k < 3; ++k) c += liver.vertices.row(liver.triangles(f, k)).transpose() / 3.0;
    if ((c - centre).norm() < 0.012)
      frame.liver_burn[static_cast<std::size_t>(f)] = static_cast<float>(kCoagulatedLevel), ++burnt;
  }
  ASSERT_GT(burnt, 0);
  view.Update(frame);
  const Picture burned = render.Render(view);
  render.SaveLast("field_smooth_burn.png");

  const Eigen::Vector2d c_px = Pixel(centre);
  const auto change = [&](const Eigen::Vector2d& px) {
    return MeanLab(burned, px.x(), px.y(), 2).L - MeanLab(unburnt, px.x(), px.y(), 2).L;
  };
  int lines = 0;
  double worst_ratio = 0;
  for (int k = 0; k < 8; ++k) {
    const double angle = 2 * std::numbers::pi * k / 8;
    const Eigen::Vector2d dir(std::cos(angle), std::sin(angle));
    std::vector<double> profile;
    for (double r = 0; r <= 120; r += 2) {
      const Eigen::Vector2d px = c_px + r * dir;
      if (px.x() < 3 || px.y() < 3 || px.x() > kWidth - 3 || px.y() > kHeight - 3) break;
      profile.push_back(change(px));
    }
    if (profile.size() < 40) continue;
    const double contrast = profile.front() - profile.back();
    std::printf("line %d: %zu samples, contrast %.1f L*, last %.1f\n", k, profile.size(), contrast, profile.back());
    if (contrast < 15 || std::abs(profile.back()) > 3) continue;  // left the liver or the burn: not this line
    double step = 0;
    for (std::size_t i = 1; i < profile.size(); ++i) step = std::max(step, std::abs(profile[i] - profile[i - 1]));
    std::printf("line %d: contrast %.1f L*, largest step %.1f L* per 2 px\n", k, contrast, step);
    worst_ratio = std::max(worst_ratio, step / contrast);
    ++lines;
  }
  ASSERT_GE(lines, 4) << "the burn's edge should be crossed by most lines";
  EXPECT_LT(worst_ratio, 0.2);
}

// The physically based liver seen from the scope: the median of the pixels where visible liver
// vertices project is dark red-brown (hue 10..60 degrees in CIE L*a*b*, L* below 60, clearly
// coloured), and the wet capsule shows a highlight (some pixels far brighter, and paler, than the
// median). The Phong fallback draws the same hue.
TEST_F(RenderMaterialsTest, ThePbrLiverIsDarkRedBrownWithAWetHighlight) {
  const std::vector<Eigen::Vector3d> points = VisibleLiverPoints(10);
  ASSERT_GT(points.size(), 50u);
  for (const MaterialModel model : {MaterialModel::kPhysicallyBased, MaterialModel::kPhong}) {
    const char* name = model == MaterialModel::kPhysicallyBased ? "pbr" : "phong";
    LaparoscopeView view(scenario_, meshes_, model);
    view.SetInstrumentPose(hook_, Parked(hook_));
    view.SetInstrumentPose(grasper_, Parked(grasper_));
    OffscreenRender render(kWidth, kHeight);
    const Picture pic = render.Render(view);
    render.SaveLast(std::string("field_liver_") + name + ".png");
    std::vector<testing::Lab> seen;
    for (const Eigen::Vector3d& p : points) {
      const Eigen::Vector2d px = Pixel(p);
      seen.push_back(MeanLab(pic, px.x(), px.y(), 0));
    }
    const auto median = [&](auto key) {
      std::vector<double> v;
      for (const auto& s : seen) v.push_back(key(s));
      std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
      return v[v.size() / 2];
    };
    const double L = median([](const testing::Lab& s) { return s.L; });
    const double a = median([](const testing::Lab& s) { return s.a; });
    const double b = median([](const testing::Lab& s) { return s.b; });
    const double hue_deg = std::atan2(b, a) * 180 / std::numbers::pi;
    const double chroma = std::hypot(a, b);
    // The highlight: the brightest liver pixels of the whole picture, found by where the liver is.
    double brightest = 0, brightest_chroma = 0;
    for (const Eigen::Vector3d& p : points) {
      const Eigen::Vector2d px = Pixel(p);
      for (int dr = -6; dr <= 6; ++dr)
        for (int dc = -6; dc <= 6; ++dc) {
          const int col = static_cast<int>(px.x()) + dc, row = static_cast<int>(px.y()) + dr;
          if (!pic.contains(col, row)) continue;
          const testing::Lab lab = LabOf(pic.at(col, row));
          if (lab.L > brightest) brightest = lab.L, brightest_chroma = std::hypot(lab.a, lab.b);
        }
    }
    std::printf("%s liver: median L* %.1f, hue %.1f deg, chroma %.1f; brightest L* %.1f (chroma %.1f)\n", name, L,
                hue_deg, chroma, brightest, brightest_chroma);
    EXPECT_GT(hue_deg, 10) << name;
    EXPECT_LT(hue_deg, 60) << name;
    EXPECT_LT(L, 60) << name;
    EXPECT_GT(L, 5) << name;
    EXPECT_GT(chroma, 15) << name;
    EXPECT_GT(brightest, L + 25) << name << ": a specular highlight";
    // PBR's dielectric highlight reflects the light's white; Phong's adds to the tissue's red.
    if (model == MaterialModel::kPhysicallyBased) {
      EXPECT_LT(brightest_chroma, chroma) << name << ": the highlight is paler than the tissue";
    }
  }
}

}  // namespace
}  // namespace vesica::app
