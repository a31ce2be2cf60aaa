// vesica-anatomy: regenerates the default anatomy (data/anatomy/) and prints its mesh quality.
#include <CLI/CLI.hpp>
#include <chrono>
#include <exception>
#include <iostream>

#include "app/anatomy/anatomy_generator.h"

int main(int argc, char** argv) {
  CLI::App cli{"Regenerates the default anatomy meshes, deterministically (see docs/anatomy.md)."};
  std::string output_dir = "data/anatomy";
  cli.add_option("-o,--output", output_dir, "directory to write the meshes and ports.toml into");
  vesica::app::anatomy::AnatomyOptions options;
  cli.add_option("--tet-optimisation", options.tet_quality.optimisation_level, "TetGen -O level (0..10)")
      ->check(CLI::Range(0, 10));
  cli.add_option("--tet-radius-edge", options.tet_quality.max_radius_edge, "TetGen -q radius-edge bound")
      ->check(CLI::Range(1.05, 10.0));
  cli.add_option("--tet-min-dihedral", options.tet_quality.min_dihedral_deg, "TetGen -q/ dihedral bound, degrees")
      ->check(CLI::Range(0.0, 30.0));
  cli.add_option("--relax", options.gallbladder_relaxation_iterations, "surface relaxation rounds before TetGen")
      ->check(CLI::Range(0, 1000));
  CLI11_PARSE(cli, argc, argv);

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
