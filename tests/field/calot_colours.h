#pragma once
// What Calot's structures look like in the rendered picture (app/render/calot_actors.cpp's
// colours under the scope's light), for the image tests, and the variants' test names.

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "../app/offscreen_render.h"

namespace vesica::app::testing {

/// Yellow fat lit by the scope: red above green above blue, blue well below.
inline bool Fat(Rgb c) { return c.r > c.g + 8 && c.g > c.b + 30 && c.r > 60; }
/// The bile ducts' grey-green: green at least red, both above blue.
inline bool Duct(Rgb c) { return c.g + 3 >= c.r && c.g > c.b + 10 && c.g > 30; }
/// The artery's red.
inline bool Artery(Rgb c) { return c.r > 1.6 * c.g && c.r > 1.6 * c.b && c.r > 40; }
/// Either.
inline bool Tube(Rgb c) { return Duct(c) || Artery(c); }

/// A Calot variant's test name from its scenario file: "calot-low-insertion.toml" -> "low_insertion"
/// (what the per-variant CTests filter on).
inline std::string CalotVariantName(const ::testing::TestParamInfo<const char*>& param) {
  std::string name = std::filesystem::path(param.param).stem().string().substr(6);  // past "calot-"
  for (char& c : name)
    if (c == '-') c = '_';
  return name;
}

}  // namespace vesica::app::testing
