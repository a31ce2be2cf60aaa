// Issue 7 acceptance: a dissection session's snapshots rendered by the laparoscope view under
// Xvfb. Image checks against an independent pinhole model of the scope (screen_projection.h):
// burn darkening where the hook burned and smoke while the pedal is down, none before; the
// membrane fading with its opacity; the grasper's jaws open and closed; the slip highlight; the
// gallbladder drawn where the deformed physics puts it. The committed recording's first seconds
// replay into the view. The renderer's mechanics are checked on the overview layout
// (cholecystectomy-overview.toml: the scope looks down on the liver bed). Set
// VESICA_RENDER_TEST_OUT to a folder to keep the pictures.

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <limits>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "app/render/laparoscope_view.h"
#include "app/render/scene_meshes.h"
#include "app/render/vertex_normals.h"
#include "app/replay/session_replay.h"
#include "app/scenario/scenario_loader.h"
#include "app/session/dissection_session.h"
#include "app/session/dissection_setup.h"
#include "device/input/input_recording.h"
#include "device/input/replay_input.h"
#include "offscreen_render.h"
#include "physics/instrument/instrument_pose.h"
#include "physics/mesh/triangle_mesh.h"
#include "screen_projection.h"
#include "../field/cie_lab.h"

namespace vesica::app {
namespace {

namespace fs = std::filesystem;
using testing::Luminance;
using testing::OffscreenRender;
using testing::Picture;
using testing::Rgb;

constexpr int kWidth = 1280;
constexpr int kHeight = 720;
// The rows above the field's status strip (its labels change with the pedal and the contact).
constexpr int kFieldRows = kHeight - 40;

// ---- pixel classes (from render_colours.h; lighting scales them) ----

bool IsLiver(Rgb c) { return c.r > 40 && c.r > 1.5 * c.g && c.r > 1.5 * c.b; }
bool IsGallbladder(Rgb c) { return c.g > 40 && c.g > 1.15 * c.r && c.g > 1.3 * c.b; }
// Steel: unsaturated grey, lit.
bool IsSteel(Rgb c) {
  const int hi = std::max({c.r, c.g, c.b}), lo = std::min({c.r, c.g, c.b});
  return hi > 30 && hi - lo < 0.2 * hi;
}
// The slip highlight kSlipRgb {1, 0.35, 0} drawn emissive: saturated amber.
bool IsSlipAmber(Rgb c) { return c.r > 200 && c.g > 50 && c.g < 170 && c.b < 70; }
// The cautery glow kCauteryGlowRgb {1, 0.75, 0.35}: bright orange-white.
bool IsGlow(Rgb c) { return c.r > 230 && c.g > 150 && c.b < 0.8 * c.g && c.b > 40; }

// A pixel turned toward the smoke's grey-white (kSmokeRgb 0.86, 0.86, 0.84): green and blue rise
// together (tissue is red, the glow is orange, char is dark: none of them does that).
bool TurnedSmoky(Rgb before, Rgb after) {
  const int dg = after.g - before.g, db = after.b - before.b;
  return dg >= 12 && db >= 12 && std::abs(dg - db) <= 0.35 * std::max(dg, db);
}

// Pixel (col, row) and its 13 x 13 neighbourhood are liver (away from other organs' edges).
bool LiverAround(const Picture& pic, int col, int row) {
  for (int r = row - 6; r <= row + 6; ++r)
    for (int c = col - 6; c <= col + 6; ++c)
      if (!pic.contains(c, r) || !IsLiver(pic.at(c, r))) return false;
  return true;
}

double Distance(Eigen::Vector2d px, int col, int row) { return (Eigen::Vector2d(col + 0.5, row + 0.5) - px).norm(); }

/// Visits every pixel within radius of px.
void ForDisc(Eigen::Vector2d px, double radius, const std::function<void(int, int)>& f) {
  for (int row = static_cast<int>(px.y() - radius) - 1; row <= static_cast<int>(px.y() + radius) + 1; ++row)
    for (int col = static_cast<int>(px.x() - radius) - 1; col <= static_cast<int>(px.x() + radius) + 1; ++col)
      if (col >= 0 && row >= 0 && col < kWidth && row < kHeight && Distance(px, col, row) <= radius) f(col, row);
}

// Pixels covered by a mesh's projection (every triangle rasterised).
std::vector<bool> Footprint(const physics::Vertices& V, const physics::Triangles& F, const LaparoscopeConfig& scope) {
  std::vector<bool> mask(static_cast<std::size_t>(kWidth) * kHeight, false);
  std::vector<Eigen::Vector2d> px(static_cast<std::size_t>(V.rows()));
  for (Eigen::Index v = 0; v < V.rows(); ++v)
    px[static_cast<std::size_t>(v)] = testing::ProjectToPixel(scope, V.row(v).transpose(), kWidth, kHeight);
  const auto cross = [](Eigen::Vector2d u, Eigen::Vector2d v) { return u.x() * v.y() - u.y() * v.x(); };
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const Eigen::Vector2d a = px[F(f, 0)], b = px[F(f, 1)], c = px[F(f, 2)];
    const double area = cross(b - a, c - a);
    if (std::abs(area) < 1e-12) continue;
    const int c0 = std::max(0, static_cast<int>(std::floor(std::min({a.x(), b.x(), c.x()}))));
    const int c1 = std::min(kWidth - 1, static_cast<int>(std::ceil(std::max({a.x(), b.x(), c.x()}))));
    const int r0 = std::max(0, static_cast<int>(std::floor(std::min({a.y(), b.y(), c.y()}))));
    const int r1 = std::min(kHeight - 1, static_cast<int>(std::ceil(std::max({a.y(), b.y(), c.y()}))));
    for (int row = r0; row <= r1; ++row)
      for (int col = c0; col <= c1; ++col) {
        const Eigen::Vector2d p(col + 0.5, row + 0.5);
        const double u = cross(b - a, p - a) / area, w = cross(c - b, p - b) / area, t = cross(a - c, p - c) / area;
        if (u >= 0 && w >= 0 && t >= 0) mask[static_cast<std::size_t>(row) * kWidth + col] = true;
      }
  }
  return mask;
}

// Möller-Trumbore: does the open segment p -> q cross triangle (a, b, c)?
bool SegmentHitsTriangle(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Vector3d& a,
                         const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const Eigen::Vector3d d = q - p, e1 = b - a, e2 = c - a;
  const Eigen::Vector3d h = d.cross(e2);
  const double det = e1.dot(h);
  if (std::abs(det) < 1e-15) return false;
  const Eigen::Vector3d s = p - a;
  const double u = s.dot(h) / det;
  if (u < 0 || u > 1) return false;
  const Eigen::Vector3d qv = s.cross(e1);
  const double v = d.dot(qv) / det;
  if (v < 0 || u + v > 1) return false;
  const double t = e2.dot(qv) / det;
  return t > 1e-6 && t < 1 - 1e-6;
}

bool SegmentClear(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const physics::TriangleMesh& mesh) {
  for (int f = 0; f < mesh.num_triangles(); ++f)
    if (SegmentHitsTriangle(p, q, mesh.vertices.row(mesh.triangles(f, 0)).transpose(),
                            mesh.vertices.row(mesh.triangles(f, 1)).transpose(),
                            mesh.vertices.row(mesh.triangles(f, 2)).transpose()))
      return false;
  return true;
}

class SessionRenderTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    scenario_ = new Scenario(LoadScenario(fs::path(VESICA_SOURCE_DIR) / "data/scenarios/cholecystectomy-overview.toml"));
    // Only the simulated organs in view: the pixel classes below are theirs (the static context's
    // fat is as bright a yellow as the hook's glow). tests/field checks the context.
    scenario_->context_organs.clear();
    scenario_->abdominal_wall.opacity = 0;
    meshes_ = new SceneMeshes(LoadSceneMeshes(*scenario_));
    model_ = BuildDissectionModelFor(*scenario_, *meshes_);
  }
  static void TearDownTestSuite() {
    model_.reset();
    delete meshes_;
    delete scenario_;
  }

  void SetUp() override {
    view_ = std::make_unique<LaparoscopeView>(*scenario_, *meshes_);
    // These checks compare the picture with the physics; the instruments' shadows (which move
    // with the tools, over tissue far from them) are tests/field's.
    view_->ShowInstrumentShadows(false);
    screen_ = std::make_unique<OffscreenRender>(kWidth, kHeight);
  }

  Picture Render(const RenderFrame& frame, const std::string& name) {
    view_->Update(frame);
    Picture pic = screen_->Render(*view_);
    if (const char* dir = std::getenv("VESICA_RENDER_TEST_OUT")) {
      const std::string test = ::testing::UnitTest::GetInstance()->current_test_info()->name();
      screen_->SaveLast(fs::path(dir) / (test + "_" + name + ".png"));
    }
    return pic;
  }

  Eigen::Vector2d Pixel(const Eigen::Vector3d& p_W) const {
    return testing::ProjectToPixel(scenario_->laparoscope, p_W, kWidth, kHeight);
  }

  static const physics::InstrumentMount& Mount(int i) { return model_->instruments[static_cast<std::size_t>(i)]; }

  // Instrument i with its shaft toward target and its tip `beyond_m` past it (< 0: short of it).
  static physics::InstrumentPose Aim(int i, const Eigen::Vector3d& target, double beyond_m) {
    const auto& m = Mount(i);
    return physics::AimAt(m.p_RemoteCentre_W, target, (target - m.p_RemoteCentre_W).norm() + beyond_m,
                          m.reference_direction_W);
  }
  // Out of the way: 2 cm through the trocar toward the scope's target.
  static physics::InstrumentPose Parked(int i) {
    const auto& m = Mount(i);
    return physics::AimAt(m.p_RemoteCentre_W, scenario_->laparoscope.look_at_m, 0.02, m.reference_direction_W);
  }

  static void StepFor(DissectionSession& session, double seconds, const physics::InstrumentPose& grasper,
                      const physics::InstrumentPose& hook, bool pedal) {
    const int steps = static_cast<int>(std::lround(seconds / model_->settings.time_step_s));
    device::InputFrame in;
    in.instruments[0].pose = grasper;
    in.instruments[1].pose = hook;
    in.instruments[1].pedal = pedal;
    for (int k = 0; k < steps; ++k) {
      in.time_s = session.time_s();
      session.Step(in);
    }
  }

  // A liver triangle to burn: in plain view of the scope (neither organ between it and the scope)
  // and of the hook's trocar (so the hook reaches it), away from the gallbladder and its membrane,
  // no corner held by ligaments; of those, the one covering most pixels (the burn shows best).
  int BurnTriangle() const {
    const physics::TriangleMesh& liver = model_->liver->rest_surface;
    const physics::TriangleMesh& gb = model_->gallbladder_boundary.surface;
    const Eigen::Vector3d scope = scenario_->laparoscope.position_m;
    const Eigen::Vector3d trocar = Mount(1).p_RemoteCentre_W;
    const physics::Vertices membrane = DissectionSession(model_, DefaultCauteryParams()).scene().membrane_points();
    std::vector<std::pair<double, int>> candidates;  // (-pixel area, triangle)
    for (int f = 0; f < liver.num_triangles(); ++f) {
      bool held = false;
      for (int k = 0; k < 3; ++k) held = held || model_->liver->layout.free_index(liver.triangles(f, k)) < 0;
      if (held) continue;
      const Eigen::Vector3d a = liver.vertices.row(liver.triangles(f, 0)).transpose();
      const Eigen::Vector3d b = liver.vertices.row(liver.triangles(f, 1)).transpose();
      const Eigen::Vector3d c = liver.vertices.row(liver.triangles(f, 2)).transpose();
      const Eigen::Vector3d n = (b - a).cross(c - a).normalized(), p = (a + b + c) / 3.0;
      if (n.dot(scope - p) <= 0 || n.dot(trocar - p) <= 0) continue;
      double near = std::numeric_limits<double>::infinity();
      for (Eigen::Index k = 0; k < gb.vertices.rows(); ++k)
        near = std::min(near, (gb.vertices.row(k).transpose() - p).norm());
      for (Eigen::Index k = 0; k < membrane.rows(); ++k)
        near = std::min(near, (membrane.row(k).transpose() - p).norm());
      if (near < 0.015) continue;
      const Eigen::Vector2d pa = Pixel(a), pb = Pixel(b), pc = Pixel(c);
      const double area_px = 0.5 * std::abs((pb - pa).x() * (pc - pa).y() - (pb - pa).y() * (pc - pa).x());
      candidates.push_back({-area_px, f});
    }
    std::sort(candidates.begin(), candidates.end());
    for (const auto& [area, f] : candidates) {
      const Eigen::Vector3d a = liver.vertices.row(liver.triangles(f, 0)).transpose();
      const Eigen::Vector3d b = liver.vertices.row(liver.triangles(f, 1)).transpose();
      const Eigen::Vector3d c = liver.vertices.row(liver.triangles(f, 2)).transpose();
      const Eigen::Vector3d lifted = (a + b + c) / 3.0 + 1e-4 * (b - a).cross(c - a).normalized();
      if (SegmentClear(lifted, scope, liver) && SegmentClear(lifted, scope, gb) &&
          SegmentClear(lifted, trocar, liver) && SegmentClear(lifted, trocar, gb)) {
        std::printf("burn triangle %d covers %.0f px\n", f, -area);
        return f;
      }
    }
    ADD_FAILURE() << "no liver triangle in view of both the scope and the hook";
    return 0;
  }

  static Eigen::Vector3d Centroid(const physics::TriangleMesh& mesh, int f) {
    return (mesh.vertices.row(mesh.triangles(f, 0)) + mesh.vertices.row(mesh.triangles(f, 1)) +
            mesh.vertices.row(mesh.triangles(f, 2)))
               .transpose() /
           3.0;
  }

  static Scenario* scenario_;
  static SceneMeshes* meshes_;
  static std::shared_ptr<const physics::DissectionModel> model_;
  std::unique_ptr<LaparoscopeView> view_;
  std::unique_ptr<OffscreenRender> screen_;
};
Scenario* SessionRenderTest::scenario_ = nullptr;
SceneMeshes* SessionRenderTest::meshes_ = nullptr;
std::shared_ptr<const physics::DissectionModel> SessionRenderTest::model_;

TEST_F(SessionRenderTest, HookBurnsDarkenTheLiverAndSmokeRisesOnlyWhileThePedalIsDown) {
  const physics::TriangleMesh& liver = model_->liver->rest_surface;
  const Eigen::Vector3d target = Centroid(liver, BurnTriangle());
  const Eigen::Vector2d target_px = Pixel(target);
  std::printf("burn target (%.4f, %.4f, %.4f) m at pixel (%.0f, %.0f)\n", target.x(), target.y(), target.z(),
              target_px.x(), target_px.y());
  DissectionSession session(model_, DefaultCauteryParams());
  const auto grasper = Parked(0);
  const auto park = Parked(1);
  const auto press = Aim(1, target, 0.0015);  // 1.5 mm into the liver

  // Rest, both instruments parked.
  StepFor(session, 0.1, grasper, park, false);
  const Picture rest = Render(session.MakeRenderFrame(), "0_rest");

  // Pressing, pedal up: the hook rests on the target; no burn, no smoke, no glow.
  StepFor(session, 1.0, grasper, press, false);  // 1 s: the gallbladder settles on its ligaments too
  std::printf("hook tip %.2f mm from the target\n", 1e3 * (session.scene().tool_tip(1) - target).norm());
  EXPECT_LT((session.scene().tool_tip(1) - target).norm(), 0.003);
  const auto& untouched = session.cautery().liver_burn().levels();
  EXPECT_EQ(*std::max_element(untouched.begin(), untouched.end()), 0.0f);
  EXPECT_TRUE(session.cautery().smoke().particles().empty());
  const Picture pressed = Render(session.MakeRenderFrame(), "1_pressed_pedal_up");
  // Still pedal up 0.3 s later: the picture stays as it was (no smoke comes, nothing darkens).
  StepFor(session, 0.3, grasper, press, false);
  const Picture pressed_later = Render(session.MakeRenderFrame(), "2_pressed_pedal_up_later");
  int smoky_before = 0, changed_before = 0, glow_before = 0;
  for (int row = 0; row < kFieldRows; ++row)
    for (int col = 0; col < kWidth; ++col) {
      smoky_before += TurnedSmoky(pressed.at(col, row), pressed_later.at(col, row));
      changed_before += std::abs(Luminance(pressed.at(col, row)) - Luminance(pressed_later.at(col, row))) > 8;
      glow_before += IsGlow(pressed_later.at(col, row));
    }
  std::printf("pedal up, pressing: %d smoky, %d changed, %d glowing pixels\n", smoky_before, changed_before,
              glow_before);
  // The hook is drawn where its shaft meets the settling tissue: its edge may move a pixel or two.
  EXPECT_LE(smoky_before, 5);
  EXPECT_LT(changed_before, 50);
  EXPECT_EQ(glow_before, 0);

  // Pedal down 1.5 s: smoke over the tip where the particles are, and the hook glows.
  StepFor(session, 1.5, grasper, press, true);
  const RenderFrame burning_frame = session.MakeRenderFrame();
  ASSERT_FALSE(burning_frame.smoke.empty());
  EXPECT_TRUE(burning_frame.instruments[1].cautery_active);
  const Picture burning = Render(burning_frame, "3_pedal_down");
  // Where the smoke must be: the particles' discs, projected (radius = size/2 over depth).
  std::vector<bool> puffs(static_cast<std::size_t>(kWidth) * kHeight, false);
  const LaparoscopeConfig& scope = scenario_->laparoscope;
  const Eigen::Vector3d forward = (scope.look_at_m - scope.position_m).normalized();
  const double focal_px = 0.5 * kHeight / std::tan(0.5 * scope.view_angle_deg * std::numbers::pi / 180.0);
  for (const SmokeSprite& sp : burning_frame.smoke) {
    const double r_px = focal_px * 0.5 * sp.size_m / (sp.p_W - scope.position_m).dot(forward);
    ForDisc(Pixel(sp.p_W), r_px + 2,
            [&](int col, int row) { puffs[static_cast<std::size_t>(row) * kWidth + col] = true; });
  }
  int smoky = 0, smoky_in_puffs = 0, glow = 0;
  for (int row = 0; row < kFieldRows; ++row)
    for (int col = 0; col < kWidth; ++col) {
      if (TurnedSmoky(pressed_later.at(col, row), burning.at(col, row))) {
        ++smoky;
        smoky_in_puffs += puffs[static_cast<std::size_t>(row) * kWidth + col];
      }
      glow += IsGlow(burning.at(col, row));
    }
  std::printf("pedal down 1.5 s: %zu particles, %d smoky pixels, %d of them inside the projected puffs; %d glowing\n",
              burning_frame.smoke.size(), smoky, smoky_in_puffs, glow);
  EXPECT_GT(smoky, 500);
  EXPECT_GT(smoky_in_puffs, 0.95 * smoky);
  EXPECT_GT(glow, 50);

  // Pedal up, hook parked, smoke gone (lifetime 1.5 s): the burn shows on the burned triangles.
  StepFor(session, 1.6, grasper, park, false);
  EXPECT_TRUE(session.cautery().smoke().particles().empty());
  const auto& levels = session.cautery().liver_burn().levels();
  physics::Triangles burned(0, 3);
  double burned_level = 0;
  for (int f = 0; f < liver.num_triangles(); ++f)
    if (levels[f] >= 0.3f) {
      burned.conservativeResize(burned.rows() + 1, 3);
      burned.row(burned.rows() - 1) = liver.triangles.row(f);
      burned_level = std::max(burned_level, static_cast<double>(levels[f]));
    }
  std::printf("liver: %lld triangles burned to >= 0.3, max %.2f\n", static_cast<long long>(burned.rows()),
              burned_level);
  ASSERT_GT(burned.rows(), 0);
  const Picture after = Render(session.MakeRenderFrame(), "4_after");
  const std::vector<bool> burn_mask = Footprint(liver.vertices, burned, scope);
  const auto inside = [&](int col, int row) {  // eroded by a pixel: edges may blend
    for (int r = row - 1; r <= row + 1; ++r)
      for (int c = col - 1; c <= col + 1; ++c)
        if (c < 0 || r < 0 || c >= kWidth || r >= kHeight || !burn_mask[static_cast<std::size_t>(r) * kWidth + c])
          return false;
    return true;
  };
  double drop_burned = 0;
  int burned_px = 0, far_changed = 0, far_px = 0, smoky_after = 0;
  for (int row = 0; row < kFieldRows; ++row)
    for (int col = 0; col < kWidth; ++col) {
      const Rgb a = rest.at(col, row), b = after.at(col, row);
      if (inside(col, row) && IsLiver(a)) {
        drop_burned += (Luminance(a) - Luminance(b)) / Luminance(a);
        ++burned_px;
      }
      // Beyond the burnt triangle and the ring around it, over which a burn fades (drawn per vertex).
      if (Distance(target_px, col, row) > 200 && LiverAround(rest, col, row) && LiverAround(after, col, row)) {
        ++far_px;
        far_changed += std::abs(Luminance(a) - Luminance(b)) > 8;
      }
      smoky_after += puffs[static_cast<std::size_t>(row) * kWidth + col] && TurnedSmoky(a, b);
    }
  const double mean_drop = burned_px ? drop_burned / burned_px : 0.0;
  std::printf(
      "after: burned pixels %d, mean relative luminance drop %.2f; liver beyond 200 px: %d of %d changed; %d smoky "
      "where the puffs were\n",
      burned_px, mean_drop, far_changed, far_px, smoky_after);
  EXPECT_GT(burned_px, 50);
  // Level >= 0.3 mixes >= 30 % char (luminance ~ 0.05 of the tissue's): ~25 % darker (0.250 measured,
  // PBR and Phong alike; PBR mixes in linear light and gamma-encodes, which compresses the drop).
  EXPECT_GT(mean_drop, 0.2);
  EXPECT_GT(far_px, 50000);
  EXPECT_EQ(far_changed, 0);
  EXPECT_EQ(smoky_after, 0);
}

// Independent of InstrumentActors: where the drawn grasper jaws' points at `along` of their 18 mm
// length lie for `pose` with jaw angle `jaw_rad` (hinged one jaw length behind the physics tip,
// so closed jaws end at it; opening across the shaft, turned by roll).
std::array<Eigen::Vector3d, 2> JawPoints(const physics::InstrumentMount& m, physics::InstrumentPose pose,
                                         double jaw_rad, double along) {
  const Eigen::Vector3d d = physics::ShaftDirection(m.reference_direction_W, pose);
  const Eigen::Vector3d tip = physics::TipPosition(m.p_RemoteCentre_W, m.reference_direction_W, pose);
  const Eigen::Vector3d side = Eigen::AngleAxisd(pose.roll_rad, d) * d.cross(Eigen::Vector3d::UnitZ()).normalized();
  const double half = 0.5 * jaw_rad, length = along * 0.018;
  const Eigen::Vector3d hinge = tip - 0.018 * d;
  return {hinge + length * (std::cos(half) * d + std::sin(half) * side),
          hinge + length * (std::cos(half) * d - std::sin(half) * side)};
}

TEST_F(SessionRenderTest, ReplayedRecordingRendersJawsClosingAndTheGallbladderWhereThePhysicsMovedIt) {
  device::InputRecording rec =
      device::ReadInputRecording(fs::path(VESICA_SOURCE_DIR) / "data/recordings/dissection-overview.csv");
  std::erase_if(rec.frames, [](const device::InputFrame& f) { return f.time_s > 2.0; });  // grasp and retract
  device::ReplayInput input(rec);
  DissectionSession session(model_, DefaultCauteryParams());
  RenderFrame open_frame;
  RunReplay(session, input, [&](const DissectionSession& s, const SessionStepReport&) {
    if (open_frame.instruments.empty() && s.time_s() >= 0.25) open_frame = s.MakeRenderFrame();
  });
  const RenderFrame closed_frame = session.MakeRenderFrame();
  ASSERT_FALSE(open_frame.instruments.empty());
  EXPECT_NEAR(open_frame.instruments[0].pose.jaw_angle_rad, 0.5, 1e-9);
  EXPECT_EQ(closed_frame.instruments[0].pose.jaw_angle_rad, 0.0);
  EXPECT_TRUE(closed_frame.instruments[0].grasping);
  const Picture open = Render(open_frame, "open");
  const Picture closed = Render(closed_frame, "closed");

  // Jaws: steel where the open jaws project (both), and in the closed frame none where its jaws
  // would be if open, steel where the closed jaws are.
  const auto steel_near = [](const Picture& pic, Eigen::Vector2d px) {
    int n = 0;
    ForDisc(px, 2.0, [&](int col, int row) { n += IsSteel(pic.at(col, row)); });
    return n;
  };
  const auto& m = Mount(0);
  int open_hits = 0, closed_open_hits = 0, closed_hits = 0;
  for (double along : {0.3, 0.5, 0.7}) {
    for (const auto& p : JawPoints(m, open_frame.instruments[0].pose, 0.5, along))
      open_hits += steel_near(open, Pixel(p)) > 0;
    closed_hits += steel_near(closed, Pixel(JawPoints(m, closed_frame.instruments[0].pose, 0.0, along)[0])) > 0;
  }
  for (double along : {0.9, 1.0})  // >= 4 mm off the closed jaws (each a 4 mm wide, fenestrated blade)
    for (const auto& p : JawPoints(m, closed_frame.instruments[0].pose, 0.5, along))
      closed_open_hits += steel_near(closed, Pixel(p)) > 0;
  std::printf("jaw points on steel: open %d/6, closed frame at open-jaw points %d/4, at closed-jaw points %d/3\n",
              open_hits, closed_open_hits, closed_hits);
  EXPECT_GE(open_hits, 5);
  EXPECT_EQ(closed_open_hits, 0);
  EXPECT_GE(closed_hits, 2);

  // Deformed gallbladder: green where the retracted physics surface projects, not where it rested.
  const physics::Triangles& gbt = model_->gallbladder_boundary.surface.triangles;
  const std::vector<bool> rest_gb =
      Footprint(model_->gallbladder_boundary.surface.vertices, gbt, scenario_->laparoscope);
  const std::vector<bool> moved_gb = Footprint(closed_frame.gallbladder_vertices, gbt, scenario_->laparoscope);
  int moved_px = 0, moved_green = 0, left_px = 0, left_green = 0, changed = 0;
  for (int row = 0; row < kHeight; ++row)
    for (int col = 0; col < kWidth; ++col) {
      const std::size_t i = static_cast<std::size_t>(row) * kWidth + col;
      const bool green = IsGallbladder(closed.at(col, row));
      if (moved_gb[i]) {
        ++moved_px;
        moved_green += green;
      } else if (rest_gb[i]) {
        ++left_px;
        left_green += green;
      }
      changed += std::abs(Luminance(open.at(col, row)) - Luminance(closed.at(col, row))) > 8;
    }
  std::printf("gallbladder: %d/%d green inside the moved silhouette; %d/%d green where it left; %d pixels changed\n",
              moved_green, moved_px, left_green, left_px, changed);
  EXPECT_GT(left_px, 500) << "the retraction should move the gallbladder visibly";
  EXPECT_GT(moved_green, 0.6 * moved_px);
  EXPECT_LT(left_green, 0.1 * left_px);
  EXPECT_GT(changed, 0.01 * kWidth * kHeight);

  // Slip highlight: the same frame with a recent slip paints the jaws amber, near the grasper tip.
  RenderFrame slipping = open_frame;
  slipping.instruments[0].slipping = true;
  const Picture slip = Render(slipping, "slip");
  const Eigen::Vector2d tip_px =
      Pixel(physics::TipPosition(m.p_RemoteCentre_W, m.reference_direction_W, open_frame.instruments[0].pose));
  int amber = 0, amber_near = 0, amber_before = 0;
  for (int row = 0; row < kHeight; ++row)
    for (int col = 0; col < kWidth; ++col) {
      amber_before += IsSlipAmber(open.at(col, row));
      // The field's status strip (the bottom 40 rows) says "GRASP SLIPPED" in the same amber.
      if (IsSlipAmber(slip.at(col, row)) && row < kFieldRows) {
        ++amber;
        amber_near += Distance(tip_px, col, row) < 120;  // the 18 mm jaws span ~100 px from the scope's tip
      }
    }
  std::printf("slip: %d amber pixels (%d within 120 px of the grasper tip), %d without the slip\n", amber, amber_near,
              amber_before);
  EXPECT_EQ(amber_before, 0);
  EXPECT_GT(amber, 40);
  EXPECT_EQ(amber_near, amber);
}

// Issue 30: a burn at a point whitens first (coagulation), then darkens to an obvious change of
// colour (CIE Delta E >= 20 after 2 s); the smoke's share of the view rises while the pedal is
// down and falls below 2 % within 1.6 s of letting go (the puffs live 1.5 s). Smoke coverage is
// the share of the field's pixels that differ (Delta E > 3) from the same frame drawn without
// its smoke.
TEST_F(SessionRenderTest, BurnsWhitenThenDarkenAndSmokeClearsAfterThePedal) {
  const physics::TriangleMesh& liver = model_->liver->rest_surface;
  const Eigen::Vector3d target = Centroid(liver, BurnTriangle());
  const Eigen::Vector2d target_px = Pixel(target);
  DissectionSession session(model_, DefaultCauteryParams());
  const auto grasper = Parked(0);
  const auto press = Aim(1, target, 0.0015);
  StepFor(session, 1.0, grasper, press, false);
  // The burn is looked at with the hook lifted off it (the tool would cover it) and no smoke.
  const auto without_smoke = [&](RenderFrame f) {
    f.smoke.clear();
    return f;
  };
  const auto burn_view = [&](RenderFrame f) {
    f.smoke.clear();
    f.instruments[1].pose = Parked(1);
    f.instruments[1].past_contact_m = 0;
    f.instruments[1].cautery_active = false;
    return f;
  };
  const auto mean_lab = [&](const Picture& pic) {  // the 7 x 7 pixels at the burn
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (int dr = -3; dr <= 3; ++dr)
      for (int dc = -3; dc <= 3; ++dc) {
        const Rgb c = pic.at(static_cast<int>(target_px.x()) + dc, static_cast<int>(target_px.y()) + dr);
        const testing::Lab lab = testing::SrgbToLab(c.r, c.g, c.b);
        sum += Eigen::Vector3d(lab.L, lab.a, lab.b);
      }
    const Eigen::Vector3d m = sum / 49.0;
    return testing::Lab{m.x(), m.y(), m.z()};
  };
  const auto coverage = [&](const RenderFrame& f) {
    if (f.smoke.empty()) return 0.0;
    const Picture with = Render(f, "smoke");
    const Picture clear = Render(without_smoke(f), "no_smoke");
    int covered = 0;
    for (int row = 0; row < kFieldRows; ++row)
      for (int col = 0; col < kWidth; ++col) {
        const Rgb a = with.at(col, row), b = clear.at(col, row);
        covered += testing::DeltaE76(testing::SrgbToLab(a.r, a.g, a.b), testing::SrgbToLab(b.r, b.g, b.b)) > 3;
      }
    return static_cast<double>(covered) / (static_cast<double>(kFieldRows) * kWidth);
  };
  const testing::Lab unburnt = mean_lab(Render(burn_view(session.MakeRenderFrame()), "unburnt"));

  // Pedal down: 0.3 s coagulates (whiter), 2 s chars (darker by Delta E >= 20).
  StepFor(session, 0.3, grasper, press, true);
  const testing::Lab early = mean_lab(Render(burn_view(session.MakeRenderFrame()), "burn_0.3s"));
  const double smoke_early = coverage(session.MakeRenderFrame());
  StepFor(session, 1.7, grasper, press, true);
  const testing::Lab late = mean_lab(Render(burn_view(session.MakeRenderFrame()), "burn_2s"));
  const double smoke_late = coverage(session.MakeRenderFrame());
  std::printf("burn at (%.0f, %.0f): L* %.1f unburnt, %.1f after 0.3 s, %.1f after 2 s (dE %.1f); smoke %.2f %% of "
              "the view at 0.3 s, %.2f %% at 2 s\n",
              target_px.x(), target_px.y(), unburnt.L, early.L, late.L, testing::DeltaE76(unburnt, late),
              100 * smoke_early, 100 * smoke_late);
  EXPECT_GT(early.L, unburnt.L + 5) << "a fresh burn whitens";
  EXPECT_LT(late.L, unburnt.L) << "a long burn darkens";
  EXPECT_GE(testing::DeltaE76(unburnt, late), 20.0);
  EXPECT_GT(smoke_late, smoke_early) << "smoke builds up while the pedal is down";
  EXPECT_GT(smoke_late, 0.005);

  // Pedal up: the plume thins and is gone below 2 % of the view within 1.6 s.
  StepFor(session, 0.5, grasper, press, false);
  const double smoke_after_05 = coverage(session.MakeRenderFrame());
  StepFor(session, 1.1, grasper, press, false);
  const double smoke_after_16 = coverage(session.MakeRenderFrame());
  std::printf("smoke after the pedal: %.2f %% at 0.5 s, %.2f %% at 1.6 s\n", 100 * smoke_after_05,
              100 * smoke_after_16);
  EXPECT_LT(smoke_after_05, smoke_late);
  EXPECT_LT(smoke_after_16, 0.02);
}

// The retracted frame of the recording at three membrane opacities.
TEST_F(SessionRenderTest, MembraneFadesWithItsOpacity) {
  device::InputRecording rec =
      device::ReadInputRecording(fs::path(VESICA_SOURCE_DIR) / "data/recordings/dissection-overview.csv");
  std::erase_if(rec.frames, [](const device::InputFrame& f) { return f.time_s > 2.0; });
  device::ReplayInput input(rec);
  DissectionSession session(model_, DefaultCauteryParams());
  RunReplay(session, input);
  RenderFrame frame = session.MakeRenderFrame();
  ASSERT_GT(frame.membrane_triangles.rows(), 0);
  // The gallbladder covers its membrane from the scope: drawn 0.5 m away, the sheet shows.
  frame.gallbladder_vertices.col(2).array() += 0.5;
  const auto with_opacity = [&](float o, const std::string& name) {
    frame.membrane_opacity.assign(static_cast<std::size_t>(frame.membrane_triangles.rows()), o);
    return Render(frame, name);
  };
  const Picture full = with_opacity(1.0f, "opacity_1");
  const Picture half = with_opacity(0.5f, "opacity_0.5");
  const Picture gone = with_opacity(0.0f, "opacity_0");
  double d_full = 0, d_half = 0;
  int membrane_px = 0;
  for (int row = 0; row < kHeight; ++row)
    for (int col = 0; col < kWidth; ++col) {
      const double lf = Luminance(full.at(col, row)) - Luminance(gone.at(col, row));
      if (std::abs(lf) < 10) continue;
      ++membrane_px;
      d_full += lf;
      d_half += Luminance(half.at(col, row)) - Luminance(gone.at(col, row));
    }
  std::printf("membrane: %d pixels, half-opacity contrast / full = %.3f\n", membrane_px, d_half / d_full);
  // Blending: pixel = a M + (1 - a) B, so the contrast against the removed membrane scales with a.
  EXPECT_GT(membrane_px, 200);
  EXPECT_NEAR(d_half / d_full, 0.5, 0.08);
}

}  // namespace
}  // namespace vesica::app
