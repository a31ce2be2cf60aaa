// vesica-script-calot: plays the scripted Calot surgeon (calot_scripted_surgeon.h) on a Calot
// scenario, prints the case's outcome and, with -o, writes its input as a recording
// (docs/recording.md) that vesica-replay plays back.
//   vesica-script-calot -s data/scenarios/calot-standard.toml [--script correct] [-o FILE] [--every N]

#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <map>

#include "app/calot/case_outcome.h"
#include "app/render/scene_meshes.h"
#include "app/replay/calot_scripted_surgeon.h"
#include "app/replay/script_recording.h"
#include "app/scenario/scenario_loader.h"
#include "app/session/dissection_setup.h"

int main(int argc, char** argv) {
  using vesica::app::CalotScript;
  CLI::App cli{"Vesica: the scripted Calot's triangle surgeon"};
  std::string scenario_path, out;
  CalotScript script = CalotScript::kCorrectDissection;
  const std::map<std::string, CalotScript> scripts{{"correct", CalotScript::kCorrectDissection},
                                                   {"clip-before-view", CalotScript::kClipBeforeCriticalView},
                                                   {"artery-cut-unclipped", CalotScript::kArteryCutWithoutClips},
                                                   {"clip-common-bile-duct", CalotScript::kClipCommonBileDuct}};
  int every = 1;
  double max_s = 600;
  cli.add_option("-s,--scenario", scenario_path, "Calot scenario file (TOML, with [calot_triangle])")->required();
  cli.add_option("--script", script, "what the surgeon does")->transform(CLI::CheckedTransformer(scripts));
  cli.add_option("-o,--output", out, "recording to write");
  vesica::app::AddScriptRunOptions(cli, every, max_s);
  CLI11_PARSE(cli, argc, argv);
  try {
    const vesica::app::Scenario scenario = vesica::app::LoadScenario(scenario_path);
    const auto setup = vesica::app::CalotSessionSetupFor(scenario);
    if (!setup) {
      spdlog::error("{}: the scenario has no [calot_triangle]", scenario_path);
      return 2;
    }
    const auto model = vesica::app::BuildDissectionModelFor(scenario, vesica::app::LoadSceneMeshes(scenario));
    vesica::app::DissectionSession session(model, vesica::app::DefaultCauteryParams(), setup);
    vesica::app::CalotSurgeonSettings settings;
    settings.log_progress = true;
    settings.max_session_s = max_s;
    settings.scope_eye_W = setup->camera.p_Eye_W_m;
    const auto frames = vesica::app::RunScriptedCalot(session, script, settings);
    if (!out.empty()) vesica::app::WriteScriptRecording(out, scenario.name, frames, every);
    const vesica::app::calot::CaseOutcome outcome = vesica::app::calot::JudgeCase(*session.calot_metrics());
    std::printf("%s, %s: %zu steps, %.2f s: %s\n", scenario_path.c_str(), vesica::app::CalotScriptName(script).c_str(),
                frames.size(), session.time_s(), vesica::app::calot::OutcomeHeadline(outcome).c_str());
    for (const auto& reason : outcome.reasons) std::printf("  %s\n", reason.text.c_str());
    return outcome.passed ? 0 : 1;
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    return 2;
  }
}
