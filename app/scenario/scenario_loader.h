#pragma once
// Reads a scenario TOML file (toml++) into a Scenario, checking every key at the door.
// Errors are ScenarioError with "FILE:LINE: KEY: what is wrong", e.g.
//   data/scenarios/x.toml:12: gallbladder.poisson_ratio: must be in (-1, 0.5), got 0.5

#include <filesystem>
#include <stdexcept>
#include <string_view>

#include "app/scenario/scenario.h"

namespace vesica::app {

class ScenarioError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Loads and validates a scenario; relative mesh and replay paths resolve against the file's folder.
/// Mesh files must exist (their contents are checked when the meshes are loaded).
Scenario LoadScenario(const std::filesystem::path& path);

/// Same, from text (tests); `source_name` stands in the messages and `base_dir` resolves paths.
Scenario ParseScenario(std::string_view text, const std::filesystem::path& source_name,
                       const std::filesystem::path& base_dir);

/// The default cholecystectomy scenario shipped in data/scenarios/.
std::filesystem::path DefaultScenarioPath();

}  // namespace vesica::app
