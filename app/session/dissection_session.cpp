#include "app/session/dissection_session.h"

#include <algorithm>
#include <cmath>

#include "app/calot/calot_session_metrics.h"

namespace vesica::app {

namespace {
fx::CauterySurfaces SurfacesOf(const physics::DissectionModel& model, const physics::DissectionScene& scene) {
  fx::CauterySurfaces s;
  s.liver = model.liver->rest_surface;
  s.gallbladder = model.gallbladder_boundary.surface;
  s.membrane.vertices = scene.membrane_points();
  s.membrane.triangles = model.tissue.membrane.triangles;
  s.membrane_element_springs.resize(static_cast<size_t>(model.tissue.membrane.triangles.rows()));
  for (Eigen::Index e = 0; e < model.tissue.membrane.springs.rows(); ++e)
    s.membrane_element_springs[static_cast<size_t>(e)] = {model.tissue.membrane.springs(e, 0),
                                                          model.tissue.membrane.springs(e, 1)};
  s.num_springs = static_cast<int>(model.tissue.springs.size());
  return s;
}
}  // namespace

DissectionSession::DissectionSession(std::shared_ptr<const physics::DissectionModel> model,
                                     const fx::CauteryParams& cautery, const std::optional<CalotSessionSetup>& calot)
    : model_(std::move(model)), scene_(model_), cautery_(SurfacesOf(*model_, scene_), cautery) {
  metrics_.springs_total = static_cast<int>(model_->tissue.springs.size());
  if (calot) {
    calot_ = std::make_unique<CalotTriangleStep>(*calot, scene_);
    scene_.SetOutsideLoad(calot_->neck_nodes(), calot_->tubes().NeckStiffness_N_per_m());
  }
}

fx::CauteryContact DissectionSession::CauteryContactFor(const physics::ToolTouch& touch, bool pedal) const {
  fx::CauteryContact c;
  c.pedal_down = pedal;
  c.dt_s = model_->settings.time_step_s;
  c.p_WTip_W = touch.p_Tip_W;
  // Membrane first: it lies between the organs, the hook is there to burn it.
  std::vector<int> alive;
  for (const int e : touch.membrane_elements)
    if (!cautery_.membrane().element_removed(e)) alive.push_back(e);
  if (!alive.empty()) {
    c.surface = fx::CauterySurface::kMembrane;
    c.element = alive.front();
    c.more_membrane_elements.assign(alive.begin() + 1, alive.end());
  } else if (touch.surface != physics::TouchedSurface::kNone) {
    c.surface = touch.surface == physics::TouchedSurface::kLiver ? fx::CauterySurface::kLiver
                                                                 : fx::CauterySurface::kGallbladder;
    c.element = touch.triangle;
    c.barycentric = touch.weights.cwiseMax(0.0) / touch.weights.cwiseMax(0.0).sum();
  }
  return c;
}

SessionStepReport DissectionSession::Step(const device::InputFrame& input) {
  std::array<physics::InstrumentPose, 2> poses;
  bool clamped = false;
  for (size_t i = 0; i < 2; ++i) {
    poses[i] = input.instruments[i].pose;
    // Non-finite and negative values are the scene's to refuse.
    if (std::isfinite(poses[i].insertion_m) && poses[i].insertion_m > kMaxInsertion_m) {
      poses[i].insertion_m = kMaxInsertion_m;
      clamped = true;
    }
  }
  SessionStepReport report;
  report.physics = scene_.Step(poses);  // throws before any change for a bad pose
  if (clamped) ++clamped_inputs_;
  const double h = model_->settings.time_step_s;

  // Cautery by the hook (instrument 1); burn maps follow the deformed surfaces.
  cautery_.mutable_liver_burn().UpdateGeometry(scene_.liver_positions());
  cautery_.mutable_gallbladder_burn().UpdateGeometry(scene_.gallbladder_surface_positions());
  // Only the hook burns: with the clip applier or the scissors in the port the pedal does nothing.
  const bool pedal = input.instruments[1].pedal && input.right_tool == physics::InstrumentTool::kCauteryHook;
  report.cautery = CauteryContactFor(report.physics.touches[1], pedal);
  cautery_.Step(report.cautery);
  cautery_active_ = report.cautery.active();
  const auto& cuts = cautery_.membrane().spring_cuts();
  for (; spring_cuts_applied_ < cuts.size(); ++spring_cuts_applied_) {
    scene_.CutSpring(cuts[spring_cuts_applied_].spring);
    ++report.springs_cut;
  }

  if (calot_) {
    calot_->Step(scene_, input, pedal);
    // The tubes pull the neck back from the next step on; a cut tube stops pulling.
    scene_.SetOutsideLoad(calot_->neck_nodes(), calot_->tubes().NeckStiffness_N_per_m());
    scene_.SetOutsideLoadForce(calot_->tubes().NeckForce_N());
  }

  // Where the tools are drawn: stopped at the first surface their shafts meet.
  const std::array<double, 2> drawn =
      drawn_tool_limit_.Update(poses, scene_.liver_positions(), scene_.gallbladder_surface_positions());
  for (size_t i = 0; i < 2; ++i) past_contact_m_[i] = poses[i].insertion_m - drawn[i];

  // Metrics.
  for (size_t i = 0; i < 2; ++i) {
    const Eigen::Vector3d tip = scene_.tool_tip(static_cast<int>(i));
    if (started_) (i == 0 ? metrics_.path_length_left_m : metrics_.path_length_right_m) += (tip - last_tip_[i]).norm();
    last_tip_[i] = tip;
    const double f = report.physics.tool_force_N[i].norm();
    metrics_.max_force_N = std::max(metrics_.max_force_N, f);
    if (f > 0) {
      force_sum_N_ += f;
      ++force_samples_;
    }
  }
  if (report.physics.grasp.slipped > 0) last_slip_s_[0] = scene_.time_s();
  if (pedal) metrics_.cautery_on_s += h;
  last_input_ = input.instruments;
  last_right_tool_ = input.right_tool;
  for (size_t i = 0; i < 2; ++i) last_input_[i].pose = poses[i];  // drawn where the physics has it
  started_ = true;
  return report;
}

SessionMetrics DissectionSession::metrics() const {
  SessionMetrics m = metrics_;
  m.duration_s = scene_.time_s();
  m.slips = scene_.grasp().total_slips();
  m.liver_damage_m2 = cautery_.liver_burn().damaged_area_m2();
  m.gallbladder_damage_m2 = cautery_.gallbladder_burn().damaged_area_m2();
  m.mean_force_N = force_samples_ > 0 ? force_sum_N_ / static_cast<double>(force_samples_) : 0.0;
  const auto& health = cautery_.membrane().health();
  const auto removed = std::count(health.begin(), health.end(), 0.0f);
  m.tissue_removed_fraction = health.empty() ? 0.0 : static_cast<double>(removed) / static_cast<double>(health.size());
  m.springs_cut = m.springs_total - scene_.tissue().num_alive();
  m.gallbladder_free = scene_.gallbladder_free();
  const auto& gb = cautery_.gallbladder_burn();
  for (int e = 0; e < gb.num_elements() && !m.perforation; ++e) m.perforation = gb.level(e) >= kPerforationLevel;
  m.success = m.gallbladder_free && !m.perforation;
  if (calot_) {
    calot::StoreCalotMetrics(calot_->metrics(), m);
    m.success = m.success && m.calot_passed;
  }
  return m;
}

RenderFrame DissectionSession::MakeRenderFrame() const {
  RenderFrame f;
  f.liver_vertices = scene_.liver_positions();
  f.gallbladder_vertices = scene_.gallbladder_surface_positions();
  f.liver_burn = cautery_.liver_burn().levels();
  f.gallbladder_burn = cautery_.gallbladder_burn().levels();
  f.membrane_vertices = scene_.membrane_points();
  f.membrane_triangles = model_->tissue.membrane.triangles;
  f.membrane_opacity = cautery_.membrane().health();
  f.membrane_burn = cautery_.membrane_burn().levels();
  for (const fx::SmokeParticle& p : cautery_.smoke().particles()) f.smoke.push_back({p.p_W, p.size_m, p.alpha});
  for (size_t i = 0; i < 2; ++i) {
    InstrumentFrame inst;
    inst.pose = last_input_[i].pose;
    inst.pedal_down = last_input_[i].pedal;
    inst.past_contact_m = past_contact_m_[i];
    if (i == 0) {
      inst.grasping = scene_.grasp().state() == physics::GraspStateMachine::State::kHolding;
      inst.slipping = scene_.time_s() - last_slip_s_[0] < 0.5;
    } else {
      inst.cautery_active = cautery_active_;
      inst.tool = last_right_tool_;
    }
    f.instruments.push_back(inst);
  }
  if (calot_) f.calot = CalotDrawingOf(*calot_);
  return f;
}

CalotDrawing CalotDrawingOf(const CalotTriangleStep& step) {
  const physics::calot::TriangleStructures& tubes = step.tubes();
  const physics::calot::TriangleDescription& d = tubes.description();
  CalotDrawing out;
  for (const physics::calot::TubePiece& piece : tubes.pieces()) {
    CalotTubeDrawing t;
    t.kind = d.tubes[static_cast<std::size_t>(piece.tube)].kind;
    t.radius_m = d.tubes[static_cast<std::size_t>(piece.tube)].material.outer_radius_m;
    const auto& x = piece.rod.positions_m();
    for (Eigen::Index i = 0; i < x.rows(); ++i) t.centreline_W.push_back(x.row(i).transpose());
    out.tubes.push_back(std::move(t));
  }
  for (int c = 0; c < static_cast<int>(tubes.clips().size()); ++c) {
    const physics::calot::ClipOnTube& clip = tubes.clips()[static_cast<std::size_t>(c)];
    const double h = 0.001;  // the tangent from the centreline a millimetre either side
    const Eigen::Vector3d along = tubes.PositionAt(clip.tube, clip.s_m + h) - tubes.PositionAt(clip.tube, clip.s_m - h);
    out.clips.push_back({tubes.ClipPosition(c), along.norm() > 0 ? along.normalized() : Eigen::Vector3d::UnitX(),
                         d.tubes[static_cast<std::size_t>(clip.tube)].material.outer_radius_m});
  }
  const physics::calot::FatLayer& fat = step.fat();
  out.fat_cell_size_m = fat.description().cell_spacing_m;
  for (std::size_t i = 0; i < fat.cells().size(); ++i)
    if (fat.cells()[i].state == physics::calot::FatCellState::kIntact) {
      out.fat_cells_W.push_back(fat.cell_positions_m()[i]);
      out.fat_cells_rest_W.push_back(fat.cells()[i].p_Rest_W_m);
    }
  for (const physics::calot::TubeLeak& leak : tubes.Leaks())
    out.leaks.push_back({leak.p_W_m, leak.fluid == physics::calot::Fluid::kBlood});
  return out;
}

}  // namespace vesica::app
