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
  CLI11_PARSE(cli, argc, argv);

  try {
    const auto start = std::chrono::steady_clock::now();
    const auto assets = vesica::app::anatomy::GenerateAnatomy({});
    vesica::app::anatomy::WriteAnatomy(assets, output_dir);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::cout << vesica::app::anatomy::SummariseAnatomy(assets) << "written to " << output_dir << " in "
              << seconds << " s\n";
  } catch (const std::exception& e) {
    std::cerr << "vesica-anatomy: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
