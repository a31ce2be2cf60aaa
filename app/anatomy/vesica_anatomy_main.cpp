// vesica-anatomy: regenerates the default anatomy (data/anatomy/) and prints its mesh quality.
#include <CLI/CLI.hpp>
#include <chrono>
#include <exception>
#include <iostream>

#include "app/anatomy/anatomy_generator.h"
#include "app/anatomy/surgeon_view_layout.h"

int main(int argc, char** argv) {
  CLI::App cli{"Regenerates the anatomy meshes, deterministically (see docs/anatomy.md)."};
  std::string output_dir = "data/anatomy";
  cli.add_option("-o,--output", output_dir, "directory to write the meshes and ports.toml into");
  std::string layout = "default";
  cli.add_option("--layout", layout,
                 "default (data/anatomy) or surgeon-view (data/anatomy/surgeon-view: the liver retracted, the fundus "
                 "over its edge)")
      ->check(CLI::IsMember({"default", "surgeon-view"}));
  // The layouts share the tet and relaxation settings: read into defaults, applied below.
  vesica::app::anatomy::AnatomyOptions tuning;
  cli.add_option("--tet-optimisation", tuning.tet_quality.optimisation_level, "TetGen -O level (0..10)")
      ->check(CLI::Range(0, 10));
  cli.add_option("--tet-radius-edge", tuning.tet_quality.max_radius_edge, "TetGen -q radius-edge bound")
      ->check(CLI::Range(1.05, 10.0));
  cli.add_option("--tet-min-dihedral", tuning.tet_quality.min_dihedral_deg, "TetGen -q/ dihedral bound, degrees")
      ->check(CLI::Range(0.0, 30.0));
  cli.add_option("--relax", tuning.gallbladder_relaxation_iterations, "surface relaxation rounds before TetGen")
      ->check(CLI::Range(0, 1000));
  CLI11_PARSE(cli, argc, argv);
  vesica::app::anatomy::AnatomyOptions options = layout == "surgeon-view"
                                                     ? vesica::app::anatomy::SurgeonViewAnatomyOptions()
                                                     : vesica::app::anatomy::AnatomyOptions{};
  options.tet_quality = tuning.tet_quality;
  options.gallbladder_relaxation_iterations = tuning.gallbladder_relaxation_iterations;

  try {
    const auto start = std::chrono::steady_clock::now();
    const auto assets = vesica::app::anatomy::GenerateAnatomy(options);
    vesica::app::anatomy::WriteAnatomy(assets, output_dir);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::cout << vesica::app::anatomy::SummariseAnatomy(assets) << "written to " << output_dir << " in " << seconds
              << " s\n";
  } catch (const std::exception& e) {
    std::cerr << "vesica-anatomy: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
