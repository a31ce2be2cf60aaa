#include "app/render/laparoscope_view.h"

#include <vtkActor.h>
#include <vtkCallbackCommand.h>
#include <vtkCamera.h>
#include <vtkLight.h>
#include <vtkPNGWriter.h>
#include <vtkPropCollection.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkSmartPointer.h>
#include <vtkTexture.h>
#include <vtkWindowToImageFilter.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <optional>
#include <stdexcept>

#include "app/render/calot_actors.h"
#include "app/render/context_organs.h"
#include "app/render/display_bounds.h"
#include "app/render/display_frame.h"
#include "app/render/field_status_overlay.h"
#include "app/render/hidden_side_culling.h"
#include "app/render/instrument_actors.h"
#include "app/render/instrument_shadow.h"
#include "app/render/membrane_sheet.h"
#include "app/render/organ_surface.h"
#include "app/render/scope_light.h"
#include "app/render/scope_pose.h"
#include "app/render/smoke_sprites.h"
#include "app/render/tissue_texture.h"
#include "physics/mesh/mesh_topology.h"

namespace vesica::app {

namespace {
template <typename T>
using Ptr = vtkSmartPointer<T>;

// VTK asks each actor in each pass of each frame whether it is translucent (its opacity, its
// textures, a scan of its colour array). For the organs, the context and the instruments the
// answer is fixed once they are built (opaque colours, opacity set once): ask once and keep it.
void KeepOpaqueDecision(vtkActor* actor) {
  if (!actor->HasTranslucentPolygonalGeometry()) actor->ForceOpaqueOn();
}
}  // namespace

struct LaparoscopeView::Impl {
  MaterialModel materials = MaterialModel::kPhysicallyBased;
  Ptr<vtkRenderer> renderer = Ptr<vtkRenderer>::New();
  vtkSmartPointer<vtkTexture> tissue_texture, tissue_normals;
  Ptr<vtkLight> light = Ptr<vtkLight>::New();
  Ptr<vtkCallbackCommand> before_render = Ptr<vtkCallbackCommand>::New();
  std::vector<vtkActor*> shadow_receivers;  // the organs
  // The clipping range's box: the static context's, once; the organs and the membrane from the
  // points they draw; every other prop (instruments, smoke, Calot's triangle) asked each frame.
  std::vector<vtkProp*> static_props, props_asked_for_bounds;
  int props_sorted = -1;  // how many props the renderer had when they were sorted
  DisplayBounds static_bounds_D;
  bool shadows = true;
  std::optional<OrganSurface> liver, gallbladder, wall;
  MembraneSheet membrane;
  SmokeSprites smoke;
  std::vector<InstrumentActors> instruments;
  std::unique_ptr<CalotActors> calot;  // the scenario has Calot's triangle
  std::optional<FieldStatusOverlay> status;
  std::vector<physics::InstrumentPose> poses;
  RenderFrameSizes sizes;
  // RenderToPng's off-screen window, kept for the view's life: a window made and destroyed per
  // picture left the translucent pass drawing with another context's buffers (vesica-replay
  // --png-dir segfaulted in Mesa's swrast on its 11th picture).
  Ptr<vtkRenderWindow> png_window;

  // Before each render: the light beside the lens where the camera is now (the trainer's keys
  // move the camera), and the instruments' shadows in the camera's view coordinates.
  void PlaceLightAndShadows() {
    vtkCamera* camera = renderer->GetActiveCamera();
    Eigen::Vector3d eye, focal, up;
    camera->GetPosition(eye.data());
    camera->GetFocalPoint(focal.data());
    camera->GetViewUp(up.data());
    const Eigen::Vector3d forward = (focal - eye).normalized();
    up = (up - up.dot(forward) * forward).normalized();
    // The display frame is right-handed: the image's right is forward x up.
    const Eigen::Vector3d light_D = ScopeLightPosition(eye, forward.cross(up), up);
    light->SetPosition(light_D.data());
    light->SetFocalPoint(focal.data());
    std::vector<ShadowCaster> casters;
    for (const auto& instrument : instruments)
      casters.insert(casters.end(), instrument.shadow_casters().begin(), instrument.shadow_casters().end());
    for (vtkActor* organ : shadow_receivers) SetInstrumentShadows(organ, casters, light_D, camera, shadows);
    membrane.SortBackToFront(eye);
  }
  static void BeforeRender(vtkObject*, unsigned long, void* impl, void*) {
    static_cast<Impl*>(impl)->PlaceLightAndShadows();
  }

  // The props whose bounds are asked for each frame: all but the static context and the
  // organs and membrane, whose boxes the view keeps.
  void SortPropsForBounds() {
    const std::vector<vtkProp*> known = {liver->actor(), gallbladder->actor(), membrane.actor()};
    static_bounds_D = DisplayBounds{};
    for (vtkProp* prop : static_props) static_bounds_D.Extend(prop->GetBounds());
    props_asked_for_bounds.clear();
    vtkCollectionSimpleIterator it;
    vtkPropCollection* props = renderer->GetViewProps();
    props_sorted = props->GetNumberOfItems();
    props->InitTraversal(it);
    while (vtkProp* prop = props->GetNextProp(it))
      if (std::find(known.begin(), known.end(), prop) == known.end() &&
          std::find(static_props.begin(), static_props.end(), prop) == static_props.end())
        props_asked_for_bounds.push_back(prop);
  }

  // The camera's clipping range around what is drawn, as vtkRenderer::ResetCameraClippingRange()
  // sets it (the same box: the visible props' bounds), without asking every actor's pipeline.
  void ResetClippingRange() {
    if (renderer->GetViewProps()->GetNumberOfItems() != props_sorted) SortPropsForBounds();  // a prop added since
    DisplayBounds box = static_bounds_D;
    box.Extend(liver->bounds_D());
    box.Extend(gallbladder->bounds_D());
    if (membrane.actor()->GetVisibility()) box.Extend(membrane.bounds_D());
    for (vtkProp* prop : props_asked_for_bounds)
      if (prop->GetVisibility() && prop->GetUseBounds()) box.Extend(prop->GetBounds());
    if (!box.empty()) renderer->ResetCameraClippingRange(box.box.data());
  }
};

LaparoscopeView::LaparoscopeView(const Scenario& scenario, const SceneMeshes& meshes, MaterialModel materials)
    : impl_(std::make_unique<Impl>()) {
  impl_->materials = materials;
  const bool pbr = materials == MaterialModel::kPhysicallyBased;
  auto& r = *impl_->renderer;
  r.SetBackground(0.10, 0.03, 0.03);  // the cavity beyond the light's reach
  // Serosa detail: one generated texture, a 3 cm period on the liver, 2 cm on the gallbladder.
  impl_->tissue_texture = MakeTissueTexture(256, 7);
  impl_->liver.emplace(meshes.liver, kLiverRgb, 0.12, 1.0, impl_->tissue_texture, 0.03);
  // The physics' own boundary numbering, so RenderFrame::gallbladder_vertices maps 1:1.
  impl_->gallbladder.emplace(physics::ExtractBoundary(meshes.gallbladder).surface, kGallbladderRgb, 0.12, 1.0,
                             impl_->tissue_texture, 0.02);
  r.AddActor(impl_->liver->actor());
  r.AddActor(impl_->gallbladder->actor());
  // The liver is closed, seen from outside and dented by millimetres: its far side stays hidden.
  // (Not the gallbladder: grasped and folded, its surface may turn its back to the scope.)
  CullHiddenSide(impl_->liver->actor(), impl_->liver->poly_data());
  if (scenario.abdominal_wall.opacity > 0) {
    constexpr double kWallRgb[3] = {0.75, 0.45, 0.40};
    impl_->wall.emplace(meshes.abdominal_wall, kWallRgb, 0.12, scenario.abdominal_wall.opacity);
    r.AddActor(impl_->wall->actor());
  }
  if (pbr) {
    impl_->tissue_normals = MakeTissueNormalTexture(256, 7);  // the relief under the colour texture's vessels
    impl_->liver->UsePbr(kLiverRoughness, impl_->tissue_normals, kTissueNormalScale);
    impl_->gallbladder->UsePbr(kGallbladderRoughness, impl_->tissue_normals, kTissueNormalScale);
    if (impl_->wall) impl_->wall->UsePbr(kWallRoughness, nullptr, 0);
    // The membrane stays Phong (translucent, per-cell colour): its light share is PBR's light's.
    auto* membrane = impl_->membrane.actor()->GetProperty();
    membrane->SetDiffuse(membrane->GetDiffuse() / kPbrLightGain);
    membrane->SetSpecular(membrane->GetSpecular() / kPbrLightGain);
  }
  impl_->shadow_receivers = {impl_->liver->actor(), impl_->gallbladder->actor()};
  for (const auto& organ : MakeContextOrganActors(scenario.context_organs, pbr)) {
    r.AddActor(organ);
    impl_->shadow_receivers.push_back(organ);
    impl_->static_props.push_back(organ);
  }
  if (impl_->wall) impl_->static_props.push_back(impl_->wall->actor());
  if (scenario.calot_triangle) {  // the triangle's tubes and fat, drawn from each frame
    impl_->calot = std::make_unique<CalotActors>(pbr);
    for (vtkActor* a : impl_->calot->actors()) r.AddActor(a);
  }
  for (vtkActor* organ : impl_->shadow_receivers) ReceiveInstrumentShadows(organ);
  for (vtkActor* organ : impl_->shadow_receivers) KeepOpaqueDecision(organ);
  if (impl_->wall) KeepOpaqueDecision(impl_->wall->actor());
  r.AddActor(impl_->membrane.actor());
  r.AddActor(impl_->smoke.actor());
  // Translucency by plain alpha blending, in the order drawn (membrane, then smoke), without
  // depth peeling: under llvmpipe the peels (up to 6, each a geometry pass, full-window blends and
  // a stall on an occlusion query) were half of the main thread's frame. The picture is the same
  // where it matters: the membrane is sorted back to front before each render, and the smoke
  // puffs all have one colour, so their order does not change what they composite to. (Smoke
  // behind the membrane is drawn over it: a difference of at most alpha_m x alpha_s x colour.)
  r.SetUseDepthPeeling(0);

  const auto& scope = scenario.laparoscope;
  for (const auto& config : scenario.instruments) {
    const Eigen::Vector3d centre = scenario.trocar(config.trocar).position_m;
    const Eigen::Vector3d reference = (scope.look_at_m - centre).normalized();
    InstrumentActors ia(config, centre, reference, pbr);
    InstrumentFrame f;
    f.pose = physics::AimAt(centre, scope.look_at_m, config.initial_insertion_m, reference);
    ia.Update(f);
    for (const auto& a : ia.actors()) {
      KeepOpaqueDecision(a);
      r.AddActor(a);
    }
    impl_->poses.push_back(f.pose);
    impl_->instruments.push_back(std::move(ia));
  }
  int grasper = -1, hook = -1;
  for (std::size_t i = 0; i < scenario.instruments.size(); ++i)
    (scenario.instruments[i].kind == InstrumentKind::kGrasper ? grasper : hook) = static_cast<int>(i);
  impl_->status.emplace(&r, grasper, hook);
  impl_->sizes = {impl_->liver->num_vertices(), impl_->liver->num_triangles(), impl_->gallbladder->num_vertices(),
                  impl_->gallbladder->num_triangles(), impl_->instruments.size()};

  // The laparoscope: the camera at the scope's tip (display frame: mirrored, display_frame.h).
  const ScopePose pose = ScopePoseOf(scope);
  vtkCamera* camera = r.GetActiveCamera();
  camera->SetPosition(ToDisplay(pose.eye_W).data());
  camera->SetFocalPoint(ToDisplay(scope.look_at_m).data());
  camera->SetViewUp(ToDisplay(pose.up_W).data());
  camera->SetViewAngle(scope.view_angle_deg);
  impl_->SortPropsForBounds();
  impl_->ResetClippingRange();
  // The scope's light leaves its tip beside the lens (placed before each render, scope_light.h):
  // near tissue bright, far tissue dark. VTK's attenuation is 1 / (c0 + c1 r + c2 r^2); this one
  // is 1 at the working distance, 2.5x at the lens, 0.36x at twice the distance (an inverse
  // square softened near the tip, as a scope's diffuser does).
  r.RemoveAllLights();
  const double working_distance_m = (scope.look_at_m - pose.eye_W).norm();
  auto& light = *impl_->light;
  light.SetLightTypeToSceneLight();
  light.SetPositional(1);
  light.SetConeAngle(180);  // no cone: the whole field is lit
  light.SetAttenuationValues(0.4, 0.0, 0.6 / (working_distance_m * working_distance_m));
  light.SetIntensity(pbr ? 1.15 * kPbrLightGain : 1.15);
  r.AddLight(impl_->light);
  r.SetTwoSidedLighting(1);
  impl_->before_render->SetCallback(&Impl::BeforeRender);
  impl_->before_render->SetClientData(impl_.get());
  r.AddObserver(vtkCommand::StartEvent, impl_->before_render);
  impl_->PlaceLightAndShadows();
}

LaparoscopeView::~LaparoscopeView() { impl_->renderer->RemoveObserver(impl_->before_render); }

vtkRenderer* LaparoscopeView::renderer() { return impl_->renderer; }

MaterialModel LaparoscopeView::materials() const { return impl_->materials; }

void LaparoscopeView::ShowInstrumentShadows(bool on) { impl_->shadows = on; }

const FieldStatusOverlay& LaparoscopeView::status() const { return *impl_->status; }

const std::vector<physics::InstrumentPose>& LaparoscopeView::poses() const { return impl_->poses; }

const RenderFrameSizes& LaparoscopeView::frame_sizes() const { return impl_->sizes; }

void LaparoscopeView::SetInstrumentPose(std::size_t instrument, const physics::InstrumentPose& pose) {
  InstrumentFrame f;
  f.pose = pose;
  impl_->instruments.at(instrument).Update(f);
  impl_->poses.at(instrument) = pose;
}

void LaparoscopeView::Update(const RenderFrame& frame) {
  ValidateRenderFrame(frame, impl_->sizes);  // throws before anything changes
  auto& m = *impl_;
  m.liver->SetVertices(frame.liver_vertices);
  m.liver->SetBurn(frame.liver_burn);
  m.gallbladder->SetVertices(frame.gallbladder_vertices);
  m.gallbladder->SetBurn(frame.gallbladder_burn);
  m.membrane.Update(frame.membrane_vertices, frame.membrane_triangles, frame.membrane_opacity, frame.membrane_burn);
  m.smoke.Update(frame.smoke);
  if (m.calot) m.calot->Update(frame.calot);
  for (std::size_t i = 0; i < frame.instruments.size(); ++i) {
    m.instruments[i].Update(frame.instruments[i]);
    m.poses[i] = frame.instruments[i].pose;
  }
  m.status->Update(frame);
  // Deformed organs and moved instruments may leave the clipping range set for the last frame.
  m.ResetClippingRange();
}

vtkRenderWindow* LaparoscopeView::OffscreenWindow(int width, int height) {
  auto& window = impl_->png_window;
  if (!window) {
    window = Ptr<vtkRenderWindow>::New();
    window->SetOffScreenRendering(1);
    window->SetMultiSamples(0);    // translucent actors vanish with multisampling on Mesa
    window->SetAlphaBitPlanes(1);  // depth peeling wants destination alpha
    window->AddRenderer(impl_->renderer);
  }
  window->SetSize(width, height);
  return window;
}

void RenderToPng(LaparoscopeView& view, int width, int height, int frames, const std::filesystem::path& png) {
  vtkRenderWindow* window = view.OffscreenWindow(width, height);
  for (int i = 0; i < std::max(frames, 1); ++i) window->Render();
  auto grab = Ptr<vtkWindowToImageFilter>::New();
  grab->SetInput(window);
  grab->ReadFrontBufferOff();
  grab->Update();
  auto writer = Ptr<vtkPNGWriter>::New();
  writer->SetFileName(png.string().c_str());
  writer->SetInputConnection(grab->GetOutputPort());
  writer->Write();
  if (writer->GetErrorCode() != 0 || !std::filesystem::exists(png))
    throw std::runtime_error(png.string() + ": could not write PNG");
}

}  // namespace vesica::app
