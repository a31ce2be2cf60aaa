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

// Per pixel darkening by vessels (0 = none), drawn as random walks that wrap around the edges;
// `rng` is left where the walks end (the colour's speckle continues from there).
std::vector<float> VesselMap(int size, SplitMix& rng) {
  const auto n = static_cast<std::size_t>(size);
  std::vector<float> vessel(n * n, 0.0f);
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
          float& v =
              vessel[static_cast<std::size_t>(Wrap(cy + dy, size)) * n + static_cast<std::size_t>(Wrap(cx + dx, size))];
          v = std::max(v, w);
        }
    }
  }
  return vessel;
}

vtkSmartPointer<vtkTexture> RepeatingTexture(const std::vector<std::uint8_t>& pixels, int size) {
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

void CheckSize(int size) {
  if (size < 16 || size > 4096) throw std::invalid_argument("tissue texture: size must be in [16, 4096]");
}

}  // namespace

std::vector<std::uint8_t> TissueTexturePixels(int size, std::uint32_t seed) {
  CheckSize(size);
  const auto n = static_cast<std::size_t>(size);
  SplitMix rng{seed};
  const std::vector<float> vessel = VesselMap(size, rng);
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
  return RepeatingTexture(TissueTexturePixels(size, seed), size);
}

std::vector<std::uint8_t> TissueNormalPixels(int size, std::uint32_t seed) {
  CheckSize(size);
  const auto n = static_cast<std::size_t>(size);
  SplitMix rng{seed};
  const std::vector<float> vessel = VesselMap(size, rng);
  // Height (in pixels of relief): raised capillaries on lobules, smooth periodic value noise at
  // two scales (16 and 32 cells across the tile: 2 and 1 mm bumps on a 3 cm tile).
  std::vector<double> height(n * n);
  for (const int cells : {16, 32}) {
    std::vector<double> lattice(static_cast<std::size_t>(cells) * cells);
    for (double& v : lattice) v = rng.Uniform();
    const double amplitude = cells == 16 ? 4.0 : 2.0;
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x) {
        const double gx = static_cast<double>(x) * cells / size, gy = static_cast<double>(y) * cells / size;
        const int x0 = static_cast<int>(gx), y0 = static_cast<int>(gy);
        const auto smooth = [](double t) { return t * t * (3 - 2 * t); };
        const double tx = smooth(gx - x0), ty = smooth(gy - y0);
        const auto at = [&](int i, int j) {
          return lattice[static_cast<std::size_t>(Wrap(j, cells)) * cells + static_cast<std::size_t>(Wrap(i, cells))];
        };
        const double v = (1 - ty) * ((1 - tx) * at(x0, y0) + tx * at(x0 + 1, y0)) +
                         ty * ((1 - tx) * at(x0, y0 + 1) + tx * at(x0 + 1, y0 + 1));
        height[static_cast<std::size_t>(y) * n + static_cast<std::size_t>(x)] += amplitude * v;
      }
  }
  for (std::size_t p = 0; p < n * n; ++p) height[p] += 1.5 * vessel[p];
  std::vector<std::uint8_t> rgb(3 * n * n);
  const auto h_at = [&](int x, int y) {
    return height[static_cast<std::size_t>(Wrap(y, size)) * n + static_cast<std::size_t>(Wrap(x, size))];
  };
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const double dx = 0.5 * (h_at(x + 1, y) - h_at(x - 1, y)), dy = 0.5 * (h_at(x, y + 1) - h_at(x, y - 1));
      const double len = std::sqrt(dx * dx + dy * dy + 1.0);
      const double normal[3] = {-dx / len, -dy / len, 1.0 / len};
      const std::size_t p = 3 * (static_cast<std::size_t>(y) * n + static_cast<std::size_t>(x));
      for (int c = 0; c < 3; ++c)
        rgb[p + static_cast<std::size_t>(c)] = static_cast<std::uint8_t>(std::lround(127.5 * (normal[c] + 1.0)));
    }
  return rgb;
}

vtkSmartPointer<vtkTexture> MakeTissueNormalTexture(int size, std::uint32_t seed) {
  return RepeatingTexture(TissueNormalPixels(size, seed), size);
}

}  // namespace vesica::app
