#include "app/replay/state_digest.h"

#include <cstdio>
#include <cstring>

namespace vesica::app {

namespace {
class Fnv1a {
 public:
  void Add(const void* data, std::size_t bytes) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < bytes; ++i) {
      h_ ^= p[i];
      h_ *= 1099511628211ull;
    }
  }
  template <typename Matrix>
  void AddMatrix(const Matrix& m) {
    Add(m.data(), sizeof(typename Matrix::Scalar) * static_cast<std::size_t>(m.size()));
  }
  template <typename T>
  void AddVector(const std::vector<T>& v) {
    Add(v.data(), sizeof(T) * v.size());
  }
  std::uint64_t value() const { return h_; }

 private:
  std::uint64_t h_ = 1469598103934665603ull;
};
}  // namespace

std::uint64_t StateDigest(const DissectionSession& session) {
  Fnv1a f;
  const physics::DissectionScene& scene = session.scene();
  f.AddMatrix(scene.gallbladder().state().displacement_m);
  f.AddMatrix(scene.gallbladder().state().velocity_m_per_s);
  f.AddMatrix(scene.liver_positions());
  f.AddVector(session.cautery().liver_burn().levels());
  f.AddVector(session.cautery().gallbladder_burn().levels());
  f.AddVector(session.cautery().membrane().health());
  for (const physics::TissueSpring& s : scene.tissue().springs) {
    const char alive = s.alive ? 1 : 0;
    f.Add(&alive, 1);
  }
  for (const fx::SmokeParticle& p : session.cautery().smoke().particles()) f.AddMatrix(p.p_W);
  return f.value();
}

std::string FormatDigest(std::uint64_t digest) {
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(digest));
  return buf;
}

}  // namespace vesica::app
