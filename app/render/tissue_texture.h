#pragma once
// A procedural serosa texture for the organs: fine capillaries (thin, darker, reddish curves) and
// a faint speckle on white, tiling seamlessly. The organ's vertex colour (tissue, mottle, burn)
// is multiplied by it, so it adds surface detail without changing the hue the metrics and image
// checks rely on. Generated, not loaded: no image file to ship, identical on every machine.

#include <cstdint>
#include <vector>

#include <vtkSmartPointer.h>

class vtkTexture;

namespace vesica::app {

/// size x size RGB pixels, row-major, 8 bits per channel; periodic in both directions.
std::vector<std::uint8_t> TissueTexturePixels(int size, std::uint32_t seed);

/// The texture above as a repeating, mip-mapped vtkTexture.
vtkSmartPointer<vtkTexture> MakeTissueTexture(int size, std::uint32_t seed);

}  // namespace vesica::app
