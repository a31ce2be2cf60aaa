#pragma once
// A procedural serosa texture for the organs: fine capillaries (thin, darker, reddish curves) and
// a faint speckle on white, tiling seamlessly. The organ's vertex colour (tissue, mottle, burn)
// is multiplied by it, so it adds surface detail without changing the hue the metrics and image
// checks rely on. Generated, not loaded: no image file to ship, identical on every machine.

#include <vtkSmartPointer.h>

#include <cstdint>
#include <vector>

class vtkTexture;

namespace vesica::app {

/// size x size RGB pixels, row-major, 8 bits per channel; periodic in both directions.
std::vector<std::uint8_t> TissueTexturePixels(int size, std::uint32_t seed);

/// The texture above as a repeating, mip-mapped vtkTexture.
vtkSmartPointer<vtkTexture> MakeTissueTexture(int size, std::uint32_t seed);

/// A tangent-space normal map of the same serosa (RGB = (n + 1) / 2, z out of the surface): the
/// capillaries a little raised, and fine lobular relief, so the wet surface's highlights break up
/// as on real tissue. Same size and seed as the colour texture: the relief lies under the vessels.
std::vector<std::uint8_t> TissueNormalPixels(int size, std::uint32_t seed);

/// The normal map above as a repeating vtkTexture (linear, not sRGB).
vtkSmartPointer<vtkTexture> MakeTissueNormalTexture(int size, std::uint32_t seed);

}  // namespace vesica::app
