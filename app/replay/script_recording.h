#pragma once
// What the scripted surgeons' command lines share (vesica-script-dissection, vesica-script-calot):
// how much of the run to keep and how long to try, and writing the kept frames as a recording.

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "device/input/input_frame.h"
#include "device/input/input_recorder.h"
#include "device/input/input_recording.h"

namespace vesica::app {

/// --every N (keep every N-th physics step's input) and --max-s (give up after this much session
/// time), their defaults the variables' values.
inline void AddScriptRunOptions(CLI::App& cli, int& every, double& max_s) {
  cli.add_option("--every", every, "keep every N-th physics step's input (replay interpolates)")
      ->check(CLI::Range(1, 100))
      ->capture_default_str();
  cli.add_option("--max-s", max_s, "give up after this much session time")->capture_default_str();
}

/// Every `every`-th frame and the last, written to `path` as a recording of `scenario_name`;
/// returns how many were written.
inline std::size_t WriteScriptRecording(const std::string& path, const std::string& scenario_name,
                                        const std::vector<device::InputFrame>& frames, int every) {
  device::InputRecorder recorder(scenario_name);
  for (size_t i = 0; i < frames.size(); ++i)
    if (i % static_cast<size_t>(every) == 0 || i + 1 == frames.size()) recorder.Append(frames[i]);
  device::WriteInputRecording(path, recorder.recording());
  return recorder.recording().frames.size();
}

}  // namespace vesica::app
