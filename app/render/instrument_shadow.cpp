#include "app/render/instrument_shadow.h"

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkMatrix4x4.h>
#include <vtkShaderProperty.h>
#include <vtkUniforms.h>

#include <algorithm>
#include <string>

namespace vesica::app {

namespace {

// Closest approach of two segments (Ericson, Real-Time Collision Detection 5.1.9): x = the
// distance, y = how far along the first segment (its parameter in [0,1]).
constexpr const char* kShadowFunctions = R"(//VTK::Light::Dec
vec2 ShadowSegmentApproach(vec3 p1, vec3 q1, vec3 p2, vec3 q2) {
  vec3 d1 = q1 - p1, d2 = q2 - p2, r = p1 - p2;
  float a = dot(d1, d1), e = max(dot(d2, d2), 1e-12), f = dot(d2, r);
  float c = dot(d1, r), b = dot(d1, d2);
  float denom = a * e - b * b;
  float s = denom > 1e-14 ? clamp((b * f - c * e) / denom, 0.0, 1.0) : 0.0;
  float t = (b * s + f) / e;
  if (t < 0.0) { t = 0.0; s = clamp(-c / a, 0.0, 1.0); }
  else if (t > 1.0) { t = 1.0; s = clamp((b - c) / a, 0.0, 1.0); }
  return vec2(length(p1 + d1 * s - p2 - d2 * t), s);
}
)";

// After the lighting: the fragment keeps the light its ray to the scope's light is not denied.
// The penumbra widens with the distance behind the caster (a fibre ring ~8 % of the distance
// wide, as seen from the tissue).
constexpr const char* kShadowImpl = R"(//VTK::Light::Impl
  if (shadowEnabled != 0) {
    float lit = 1.0;
    vec3 p = vertexVC.xyz;
    float to_light = length(shadowLightVC - p);
    for (int i = 0; i < 8; ++i) {
      if (i >= shadowCount) break;
      vec2 approach = ShadowSegmentApproach(p, shadowLightVC, shadowA[i], shadowB[i]);
      float behind = approach.y * to_light;
      float soft = 0.25 * shadowRadius[i] + 0.08 * behind;
      float core = 1.0 - smoothstep(shadowRadius[i] - soft, shadowRadius[i] + soft, approach.x);
      lit = min(lit, 1.0 - shadowStrength * core);
    }
    gl_FragData[0].rgb *= lit;
  }
)";

}  // namespace

void ReceiveInstrumentShadows(vtkActor* organ) {
  vtkShaderProperty* shader = organ->GetShaderProperty();
  shader->AddFragmentShaderReplacement("//VTK::Light::Dec", true, kShadowFunctions, false);
  shader->AddFragmentShaderReplacement("//VTK::Light::Impl", true, kShadowImpl, false);
  vtkUniforms* u = shader->GetFragmentCustomUniforms();
  u->SetUniformi("shadowEnabled", 0);
  u->SetUniformi("shadowCount", 0);
  u->SetUniformf("shadowStrength", static_cast<float>(kShadowStrength));
  const float zero[3] = {0, 0, 0};
  u->SetUniform3f("shadowLightVC", zero);
  float ends[kMaxShadowCasters][3] = {};
  float radii[kMaxShadowCasters] = {};
  u->SetUniform3fv("shadowA", kMaxShadowCasters, ends);
  u->SetUniform3fv("shadowB", kMaxShadowCasters, ends);
  u->SetUniform1fv("shadowRadius", kMaxShadowCasters, radii);
}

void SetInstrumentShadows(vtkActor* organ, const std::vector<ShadowCaster>& casters, const Eigen::Vector3d& light_D,
                          vtkCamera* camera, bool enabled) {
  vtkMatrix4x4* view = camera->GetViewTransformMatrix();  // display frame -> view coordinates
  const auto to_view = [view](const Eigen::Vector3d& p, float out[3]) {
    const double in[4] = {p.x(), p.y(), p.z(), 1.0};
    double v[4];
    view->MultiplyPoint(in, v);
    for (int c = 0; c < 3; ++c) out[c] = static_cast<float>(v[c] / v[3]);
  };
  const int n = std::min(static_cast<int>(casters.size()), kMaxShadowCasters);
  float a[kMaxShadowCasters][3] = {}, b[kMaxShadowCasters][3] = {};
  float radii[kMaxShadowCasters] = {};
  for (int i = 0; i < n; ++i) {
    to_view(casters[static_cast<std::size_t>(i)].a_D, a[i]);
    to_view(casters[static_cast<std::size_t>(i)].b_D, b[i]);
    radii[i] = static_cast<float>(casters[static_cast<std::size_t>(i)].radius_m);
  }
  float light[3];
  to_view(light_D, light);
  vtkUniforms* u = organ->GetShaderProperty()->GetFragmentCustomUniforms();
  u->SetUniformi("shadowEnabled", enabled ? 1 : 0);
  u->SetUniformi("shadowCount", n);
  u->SetUniform3f("shadowLightVC", light);
  u->SetUniform3fv("shadowA", kMaxShadowCasters, a);
  u->SetUniform3fv("shadowB", kMaxShadowCasters, b);
  u->SetUniform1fv("shadowRadius", kMaxShadowCasters, radii);
}

}  // namespace vesica::app
