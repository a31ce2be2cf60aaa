#pragma once
// One trainee's dissection: the coupled physics scene, the cautery effects and the metrics,
// advanced together by one input frame per physics step (docs/architecture.md's "One physics step", then
// fx). The hook's pedal burns what its tip touches: membrane elements within its radius first
// (they fade and, once all of a spring's are gone, the spring is cut), else the liver or the
// gallbladder wall (damage). Deterministic: the same inputs give bit-identical states. While a
// session lives the process's dense algebra (OpenBLAS) runs on one thread.

#include <memory>
#include <optional>

#include "app/records/session_metrics.h"
#include "app/render/render_frame.h"
#include "app/session/calot_triangle_step.h"
#include "app/session/drawn_tool_limit.h"
#include "device/input/input_frame.h"
#include "fx/cautery_effects.h"
#include "physics/bem/dense_lu_solve.h"
#include "physics/scene/dissection_scene.h"

namespace vesica::app {

struct SessionStepReport {
  physics::DissectionStepReport physics;
  fx::CauteryContact cautery;
  int springs_cut = 0;  ///< springs removed this step
};

class DissectionSession {
 public:
  /// With `calot`, the session runs Calot's triangle (CalotTriangleStep) after the scene each
  /// step; without it nothing of the triangle exists and the session is as before, bit for bit.
  DissectionSession(std::shared_ptr<const physics::DissectionModel> model, const fx::CauteryParams& cautery,
                    const std::optional<CalotSessionSetup>& calot = std::nullopt);

  /// Advances one physics step with both instruments as in `input` (its time is not used: the
  /// session clock is steps x h). Throws std::invalid_argument (state unchanged) for a bad pose
  /// (not finite, negative insertion). An insertion beyond kMaxInsertion_m is clamped to it.
  SessionStepReport Step(const device::InputFrame& input);

  /// No laparoscopic instrument reaches deeper than this past its trocar (shafts are 0.3-0.45 m,
  /// the scenario's default 0.36 m). A deeper input (a corrupt recording, a faulty encoder) is
  /// clamped: a recorded 1e308 m made the tip path length infinite and the session unstorable.
  static constexpr double kMaxInsertion_m = 0.5;
  /// Input frames whose insertion was clamped so far.
  long clamped_inputs() const { return clamped_inputs_; }

  /// Metrics so far; success = gallbladder free without perforation (and, with the Calot step,
  /// the step passed: calot::StoreCalotMetrics fills its columns).
  SessionMetrics metrics() const;

  /// Calot's triangle (issue 36); nullptr when the scenario has none.
  const calot::CalotMetrics* calot_metrics() const { return calot_ ? &calot_->metrics() : nullptr; }
  /// The case has ended: a bile duct injury (a clip or cut on the common bile or hepatic duct).
  /// The SessionRunner then finishes the session as End() does. False without a triangle.
  bool case_ended() const { return calot_ && calot_->case_ended(); }
  /// The triangle's tubes (pieces' centrelines, clips) and fat layer, for drawing; nullptr without.
  const physics::calot::TriangleStructures* calot_tubes() const { return calot_ ? &calot_->tubes() : nullptr; }
  const physics::calot::FatLayer* calot_fat() const { return calot_ ? &calot_->fat() : nullptr; }
  const CalotTriangleStep* calot_step() const { return calot_.get(); }
  /// The snapshot the laparoscope view draws (instrument count 2, in scenario order grasper, hook).
  RenderFrame MakeRenderFrame() const;

  const physics::DissectionScene& scene() const { return scene_; }
  const fx::CauteryEffects& cautery() const { return cautery_; }
  double time_s() const { return scene_.time_s(); }
  bool gallbladder_free() const { return scene_.gallbladder_free(); }
  /// The gallbladder wall counts as perforated once an element is burnt to this level.
  static constexpr double kPerforationLevel = 0.99;

 private:
  fx::CauteryContact CauteryContactFor(const physics::ToolTouch& touch, bool pedal) const;

  // One dense-algebra thread while the session lives (the scene's background refactorisations
  // after cuts call OpenBLAS; its spinning idle workers would take the physics, haptic and render
  // threads' cores: replay p99 step 55 -> 13 ms on the 2-core machine). First member: the scene's
  // constructor factorises already.
  physics::ScopedDenseLinearAlgebraThreads dense_algebra_threads_{1};
  std::shared_ptr<const physics::DissectionModel> model_;
  physics::DissectionScene scene_;
  fx::CauteryEffects cautery_;
  DrawnToolLimit drawn_tool_limit_{*model_};
  std::array<double, 2> past_contact_m_{0, 0};  ///< commanded tip beyond where the tool is drawn
  std::size_t spring_cuts_applied_ = 0;
  std::array<device::InstrumentInput, 2> last_input_{};
  physics::InstrumentTool last_right_tool_ = physics::InstrumentTool::kCauteryHook;
  std::array<Eigen::Vector3d, 2> last_tip_{Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
  std::array<double, 2> last_slip_s_{-1e9, -1e9};
  bool cautery_active_ = false;
  bool started_ = false;
  long clamped_inputs_ = 0;
  SessionMetrics metrics_;
  std::unique_ptr<CalotTriangleStep> calot_;  // null without a triangle
  double force_sum_N_ = 0;
  long force_samples_ = 0;
};

/// What the view draws of the triangle now: each tube piece through its nodes, the clips with the
/// tube's tangent, the fat layer's intact cells, the leaking ends.
CalotDrawing CalotDrawingOf(const CalotTriangleStep& step);

}  // namespace vesica::app
