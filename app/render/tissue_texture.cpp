#include "app/render/tissue_texture.h"

#include <vtkImageData.h>
#include <vtkPointData.h>
#include <vtkTexture.h>
#include <vtkUnsignedCharArray.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace vesica::app {

namespace {

// A small counter-based generator (SplitMix64): the same pixels from every standard library.
struct SplitMix {
  std::uint64_t state;
  double Uniform() {  // [0, 1)
    std::uint64_t z = (state += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return static_cast<double>((z ^ (z >> 31)) >> 11) * 0x1.0p-53;
  }
};

int Wrap(int i, int n) { return ((i % n) + n) % n; }

}  // namespace

std::vector<std::uint8_t> TissueTexturePixels(int size, std::uint32_t seed) {
  if (size < 16 || size > 4096) throw std::invalid_argument("tissue texture: size must be in [16, 4096]");
  const auto n = static_cast<std::size_t>(size);
  // Per pixel darkening by vessels (0 = none), drawn as random walks that wrap around the edges.
  std::vector<float> vessel(n * n, 0.0f);
  SplitMix rng{seed};
  const int vessels = std::max(4, size / 20);
  for (int k = 0; k < vessels; ++k) {
    double x = rng.Uniform() * size, y = rng.Uniform() * size;
    double heading = rng.Uniform() * 2 * std::numbers::pi;
    const double depth = 0.25 + 0.2 * rng.Uniform();  // how dark this vessel is
    const int length = size / 2 + static_cast<int>(rng.Uniform() * size);
    for (int s = 0; s < length; ++s) {
      heading += 0.35 * (rng.Uniform() - 0.5);  // gentle meander
      x += std::cos(heading);
      y += std::sin(heading);
      const int cx = static_cast<int>(std::floor(x)), cy = static_cast<int>(std::floor(y));
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const double d = std::hypot(cx + dx + 0.5 - x, cy + dy + 0.5 - y);  // distance to the path
          const float w = static_cast<float>(depth * std::max(0.0, 1.0 - d / 1.2));
          float& v = vessel[static_cast<std::size_t>(Wrap(cy + dy, size)) * n + static_cast<std::size_t>(Wrap(cx + dx, size))];
          v = std::max(v, w);
        }
    }
  }
  std::vector<std::uint8_t> rgb(3 * n * n);
  for (std::size_t p = 0; p < n * n; ++p) {
    const double speckle = 1.0 - 0.06 * rng.Uniform();
    const double v = vessel[p];
    // Vessels darken green and blue more than red: reddish capillaries on any tissue colour.
    const double r = speckle * (1.0 - 0.5 * v), g = speckle * (1.0 - 1.2 * v), b = speckle * (1.0 - 1.1 * v);
    rgb[3 * p] = static_cast<std::uint8_t>(std::lround(255.0 * std::clamp(r, 0.0, 1.0)));
    rgb[3 * p + 1] = static_cast<std::uint8_t>(std::lround(255.0 * std::clamp(g, 0.0, 1.0)));
    rgb[3 * p + 2] = static_cast<std::uint8_t>(std::lround(255.0 * std::clamp(b, 0.0, 1.0)));
  }
  return rgb;
}

vtkSmartPointer<vtkTexture> MakeTissueTexture(int size, std::uint32_t seed) {
  const std::vector<std::uint8_t> pixels = TissueTexturePixels(size, seed);
  auto colours = vtkSmartPointer<vtkUnsignedCharArray>::New();
  colours->SetNumberOfComponents(3);
  colours->SetNumberOfTuples(static_cast<vtkIdType>(size) * size);
  std::copy(pixels.begin(), pixels.end(), colours->GetPointer(0));
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(size, size, 1);
  image->GetPointData()->SetScalars(colours);
  auto texture = vtkSmartPointer<vtkTexture>::New();
  texture->SetInputData(image);
  texture->SetColorModeToDirectScalars();
  texture->RepeatOn();
  texture->InterpolateOn();
  // No mipmaps: Mesa's llvmpipe (Debian 12's 22.3, the renderer under Xvfb and on machines without
  // a GPU) never returns from drawing some screen-space slivers with a mipmapped texture (a
  // one-triangle reproducer is in docs/development.md). The texture is smooth at the scope's
  // working distance, so plain linear filtering shimmers little.
  texture->MipmapOff();
  return texture;
}

}  // namespace vesica::app
