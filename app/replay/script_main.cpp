// vesica-script-dissection: plays the scripted surgeon (scripted_surgeon.h) on a scenario and
// writes its input as a recording (docs/recording.md), the one committed as
// data/recordings/dissection.csv.
//   vesica-script-dissection [-s SCENARIO] -o FILE [--every N]

#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <cstdio>

#include "app/render/scene_meshes.h"
#include "app/render/scope_pose.h"
#include "app/replay/script_recording.h"
#include "app/replay/scripted_surgeon.h"
#include "app/scenario/scenario_loader.h"
#include "app/session/dissection_setup.h"

int main(int argc, char** argv) {
  CLI::App cli{"Vesica: record the scripted dissection"};
  std::string scenario_path = vesica::app::DefaultScenarioPath().string(), out;
  int every = 4;
  double max_s = 240;
  cli.add_option("-s,--scenario", scenario_path, "scenario file (TOML)")->capture_default_str();
  cli.add_option("-o,--output", out, "recording to write")->required();
  vesica::app::AddScriptRunOptions(cli, every, max_s);
  CLI11_PARSE(cli, argc, argv);
  try {
    const vesica::app::Scenario scenario = vesica::app::LoadScenario(scenario_path);
    const auto model = vesica::app::BuildDissectionModelFor(scenario, vesica::app::LoadSceneMeshes(scenario));
    vesica::app::DissectionSession session(model, vesica::app::DefaultCauteryParams());
    vesica::app::ScriptedSurgeonSettings settings;
    settings.log_progress = true;
    settings.max_session_s = max_s;
    settings.scope_eye_W = vesica::app::ScopePoseOf(scenario.laparoscope).eye_W;
    const auto frames = vesica::app::RunScriptedDissection(session, settings);
    const std::size_t written = vesica::app::WriteScriptRecording(out, scenario.name, frames, every);
    const auto m = session.metrics();
    std::printf("%s: %zu frames, %.2f s; gallbladder free %s, springs cut %d of %d, slips %d, max force %.2f N\n",
                out.c_str(), written, m.duration_s, m.gallbladder_free ? "yes" : "no", m.springs_cut, m.springs_total,
                m.slips, m.max_force_N);
    return m.gallbladder_free ? 0 : 1;
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    return 2;
  }
}
