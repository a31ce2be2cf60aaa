#include "app/render/field_status_overlay.h"

#include <vtkRenderer.h>
#include <vtkTextActor.h>
#include <vtkTextProperty.h>

#include <algorithm>
#include <cmath>

#include "app/render/render_colours.h"

namespace vesica::app {

namespace {

// Below this the gap is the surface's own discretisation, not the hand pushing past it.
constexpr double kPastContactShown_m = 1e-3;

vtkSmartPointer<vtkTextActor> Label(vtkRenderer* renderer, int justification, double x, double y) {
  auto label = vtkSmartPointer<vtkTextActor>::New();
  label->GetPositionCoordinate()->SetCoordinateSystemToNormalizedViewport();
  label->GetPositionCoordinate()->SetValue(x, y);
  auto* p = label->GetTextProperty();
  p->SetFontFamilyToArial();
  p->SetBold(1);
  p->SetFontSize(18);
  p->SetJustification(justification);
  p->SetVerticalJustificationToBottom();
  p->SetBackgroundColor(0, 0, 0);
  p->SetBackgroundOpacity(0.45);  // legible over bright tissue, the field still seen through it
  renderer->AddActor2D(label);
  return label;
}

void Show(vtkTextActor* label, const std::string& text, const double rgb[3]) {
  label->SetInput(text.c_str());
  label->GetTextProperty()->SetColor(rgb[0], rgb[1], rgb[2]);
  label->SetVisibility(!text.empty());
}

}  // namespace

FieldStatusOverlay::FieldStatusOverlay(vtkRenderer* renderer, int grasper, int hook)
    : renderer_(renderer), grasper_(grasper), hook_(hook) {
  grasp_ = Label(renderer, VTK_TEXT_LEFT, 0.015, 0.02);
  pedal_ = Label(renderer, VTK_TEXT_RIGHT, 0.985, 0.02);
  arms_ = Label(renderer, VTK_TEXT_CENTERED, 0.5, 0.06);  // above the hands' row (Update)
  Update(RenderFrame{});
}

void FieldStatusOverlay::Update(const RenderFrame& frame) {
  // Text in proportion to the picture: 18 px at 720 rows, legible and out of the way at any size.
  const int rows = renderer_->GetSize()[1] > 0 ? renderer_->GetSize()[1] : 720;
  const int font_px = std::clamp(rows / 40, 8, 30);
  for (vtkTextActor* label : {grasp_.Get(), pedal_.Get(), arms_.Get()}) label->GetTextProperty()->SetFontSize(font_px);
  // The arms' lines stand one text row above the hands' labels: a long one ("no valid
  // calibration; run ...") must not run into them.
  arms_->GetPositionCoordinate()->SetValue(0.5, 0.02 + 1.6 * font_px / rows);
  const auto instrument = [&](int i) -> const InstrumentFrame* {
    return i >= 0 && static_cast<std::size_t>(i) < frame.instruments.size() ? &frame.instruments[i] : nullptr;
  };
  if (const InstrumentFrame* g = instrument(grasper_)) {
    if (g->slipping)
      Show(grasp_, "GRASP SLIPPED", kSlipRgb);
    else if (g->grasping)
      Show(grasp_, "grasper: holding", kStatusOkRgb);
    else
      Show(grasp_, "grasper: empty", kStatusIdleRgb);
  } else {
    Show(grasp_, "", kStatusIdleRgb);
  }
  if (const InstrumentFrame* h = instrument(hook_)) {
    // The hand past where the tool is drawn (it stops at the tissue): say by how much.
    const std::string past = h->past_contact_m >= kPastContactShown_m
                                 ? "   " + std::to_string(static_cast<int>(std::lround(1e3 * h->past_contact_m))) +
                                       " mm past contact"
                                 : "";
    const bool exchanged = physics::IsRightHandTool(h->tool) && h->tool != physics::InstrumentTool::kCauteryHook;
    if (exchanged)  // the clip applier or the scissors: no pedal to show, the jaws instead
      Show(pedal_,
           std::string(h->tool == physics::InstrumentTool::kClipApplier ? "clip applier" : "scissors") +
               (h->pose.jaw_angle_rad > 0.1 ? ": jaws open" : ": jaws closed") + past,
           past.empty() ? kStatusIdleRgb : kSlipRgb);
    else if (h->pedal_down)
      Show(pedal_, (h->cautery_active ? "CUT  (burning)" : "CUT  pedal down") + past, kCauteryGlowRgb);
    else
      Show(pedal_, "hook: pedal up" + past, past.empty() ? kStatusIdleRgb : kSlipRgb);
  } else {
    Show(pedal_, "", kStatusIdleRgb);
  }
  std::string arms;
  bool arm_fault = false;
  for (const std::string& line : frame.arm_status) {
    arms += (arms.empty() ? "" : "\n") + line;  // one arm a line
    arm_fault = arm_fault || line.find(" ok") == std::string::npos;
  }
  Show(arms_, arms, arm_fault ? kSlipRgb : kStatusIdleRgb);
}

std::string FieldStatusOverlay::grasp_text() const { return grasp_->GetVisibility() ? grasp_->GetInput() : ""; }
std::string FieldStatusOverlay::pedal_text() const { return pedal_->GetVisibility() ? pedal_->GetInput() : ""; }
std::string FieldStatusOverlay::arm_text() const { return arms_->GetVisibility() ? arms_->GetInput() : ""; }

}  // namespace vesica::app
