// vesica-register: registers a tet mesh of an organ to control points tracked on 2D slices
// (issue 35; physics/registration; docs/registration.md). Everything is read, checked and
// computed before the first file is written: bad input leaves nothing behind.
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <climits>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <iostream>
#include <optional>
#include <sstream>

#include "app/mesh_io/mesh_io.h"
#include "app/patient/patient_files.h"
#include "app/register/control_point_csv.h"
#include "app/register/registration_output.h"
#include "app/register/slice_output.h"
#include "physics/fem/fem_error.h"
#include "physics/mesh/mesh_topology.h"
#include "physics/mesh/mesh_validation.h"
#include "physics/registration/registration_fem_settings.h"
#include "physics/registration/registration_solver.h"
#include "physics/registration/slice_warp.h"

namespace {

namespace fs = std::filesystem;
namespace phys = vesica::physics;
namespace reg = vesica::app::registration;

void Progress(int done, int total) {
  constexpr int kWidth = 40;
  const int filled = total > 0 ? done * kWidth / total : kWidth;
  std::fprintf(stderr, "\r[%s%s] %d/%d frames", std::string(static_cast<size_t>(filled), '#').c_str(),
               std::string(static_cast<size_t>(kWidth - filled), ' ').c_str(), done, total);
  if (done == total) std::fputc('\n', stderr);
  std::fflush(stderr);
}

// "a:b" (inclusive frame numbers; either side may be empty).
void ParseFrames(const std::string& spec, int& first, int& last) {
  const auto colon = spec.find(':');
  const auto fail = [&] { throw reg::RegisterInputError("--frames '" + spec + "': expected FIRST:LAST"); };
  if (colon == std::string::npos) fail();
  try {
    if (colon > 0) first = std::stoi(spec.substr(0, colon));
    if (colon + 1 < spec.size()) last = std::stoi(spec.substr(colon + 1));
  } catch (const std::exception&) {
    fail();
  }
  if (first > last) fail();
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App cli{
      "Registers a tet mesh to control points tracked on 2D slices (constraint-based, real time; "
      "docs/registration.md)."};
  std::string mesh_file, points_file, out_dir, frames_spec = ":", warp_file, slice_spec;
  phys::RegistrationSettings settings;
  settings.soft_compliance_m_per_N = 0.01;
  int steps_per_frame = 10, warp_frame = -1;
  bool no_normal_check = false;
  double max_point_distance_m = 0.05;
  cli.add_option("mesh", mesh_file, "tetrahedral mesh (.vtu or .vtk, metres) at the time of the CT")->required();
  cli.add_option("points", points_file, "control points CSV: " + std::string(reg::kControlPointCsvHeader))->required();
  cli.add_option("--out", out_dir, "directory to write the registered series into (created)")->required();
  cli.add_option("--soft-compliance", settings.soft_compliance_m_per_N,
                 "W_soft = S (1 - c) / c for confidence c, m/N; 0 makes every constraint hard")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  cli.add_option("--frames", frames_spec, "FIRST:LAST frame numbers to register (inclusive)");
  cli.add_option("--steps-per-frame", steps_per_frame, "registration steps per image frame")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  cli.add_flag("--no-normal-check", no_normal_check, "pair with the nearest triangle whatever its side (Fig. 2(b))");
  cli.add_option("--max-point-distance", max_point_distance_m,
                 "a point farther than this from the mesh (m) is an input error; also the pairing's reach")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  auto* warp = cli.add_option("--warp", warp_file, "CT volume (NIfTI) to warp with the displacement field");
  cli.add_option("--slice", slice_spec, "the CT slice to warp: i:INDEX, j:INDEX or k:INDEX")->needs(warp);
  cli.add_option("--warp-frame", warp_frame, "frame whose field warps the CT (default: the last registered)")
      ->needs(warp);
  CLI11_PARSE(cli, argc, argv);
  settings.check_normals = !no_normal_check;
  settings.max_pairing_distance_m = max_point_distance_m;

  try {
    if (!warp_file.empty() && slice_spec.empty()) throw reg::RegisterInputError("--warp needs --slice");
    int first = INT_MIN, last = INT_MAX;
    ParseFrames(frames_spec, first, last);
    phys::SliceAxis slice_axis = phys::SliceAxis::kK;
    int slice_index = 0;
    if (!slice_spec.empty()) reg::ParseSliceSpec(slice_spec, slice_axis, slice_index);
    if (fs::exists(out_dir) && !fs::is_directory(out_dir))
      throw reg::RegisterInputError(out_dir + ": exists and is not a directory");

    // 1. Inputs, all checked before anything runs.
    const phys::TetrahedralMesh mesh = vesica::app::ReadTetrahedralMesh(mesh_file);
    std::shared_ptr<const phys::FemModel> model;
    try {
      model = std::make_shared<const phys::FemModel>(
          phys::BuildFemModel(mesh, phys::DefaultRegistrationFemSettings(mesh_file), {}));
    } catch (const std::exception& e) {
      throw reg::RegisterInputError(e.what());  // names the body, i.e. the mesh file
    }
    reg::ControlPointSeries series = reg::ReadControlPointCsv(points_file);
    std::vector<phys::ControlFrame> frames;
    std::vector<std::vector<int>> lines;
    for (size_t f = 0; f < series.frames.size(); ++f)
      if (series.frames[f].frame >= first && series.frames[f].frame <= last) {
        frames.push_back(series.frames[f]);
        lines.push_back(series.lines[f]);
      }
    if (frames.empty()) throw reg::RegisterInputError(points_file + ": no frame in --frames " + frames_spec);
    series = {frames, lines};
    phys::RegistrationSolver solver(model, settings);
    reg::CheckPointsNearSurface(series, points_file, solver.surface(), mesh.vertices, max_point_distance_m);
    std::optional<vesica::app::patient::PatientVolume> ct;
    if (!warp_file.empty()) ct = vesica::app::patient::ReadNiftiVolume(warp_file);

    // 2. Registration, frame by frame.
    std::vector<reg::RegisteredFrame> registered;
    const int total = static_cast<int>(series.frames.size());
    for (int f = 0; f < total; ++f) {
      const phys::ControlFrame& frame = series.frames[static_cast<size_t>(f)];
      reg::RegisteredFrame out{frame.frame, frame.time_s, static_cast<int>(frame.points.size()), {}, {}};
      for (int step = 0; step < steps_per_frame; ++step) {
        out.last_step = solver.Step(frame.points);
        if (!out.last_step.fem.accepted)
          throw std::runtime_error("frame " + std::to_string(frame.frame) + " (" + points_file + " line " +
                                   std::to_string(series.lines[static_cast<size_t>(f)].front()) +
                                   "): the FE step failed: " + out.last_step.fem.rejection_reason);
      }
      out.positions_W = solver.CurrentPositions();
      registered.push_back(std::move(out));
      Progress(f + 1, total);
    }

    // 3. The warped slice.
    std::optional<phys::WarpedSlice> original, warped;
    if (ct) {
      const reg::RegisteredFrame* source = &registered.back();
      if (warp_frame >= 0) {
        source = nullptr;
        for (const auto& r : registered)
          if (r.frame == warp_frame) source = &r;
        if (!source)
          throw reg::RegisterInputError("--warp-frame " + std::to_string(warp_frame) + " was not registered");
      }
      try {
        original = phys::WarpSlice(ct->labels, ct->hu, mesh, mesh.vertices, slice_axis, slice_index);
        warped = phys::WarpSlice(ct->labels, ct->hu, mesh, source->positions_W, slice_axis, slice_index);
      } catch (const std::invalid_argument& e) {
        throw reg::RegisterInputError(warp_file + ": " + e.what());
      }
    }

    // 4. Output.
    fs::create_directories(out_dir);
    reg::WriteRegistrationOutputs(out_dir, mesh, registered);
    if (warped) {
      const std::string stem = "slice_" + slice_spec.substr(0, 1) + std::to_string(slice_index);
      reg::WriteSlice(*original, ct->labels, fs::path(out_dir) / (stem + "_original"));
      reg::WriteSlice(*warped, ct->labels, fs::path(out_dir) / (stem + "_warped"));
    }
    const auto& last_step = registered.back().last_step;
    std::printf("%d frames registered (%d steps each); last frame: %d/%d points paired, gap mean %.3f max %.3f mm\n",
                total, steps_per_frame, last_step.paired_points, registered.back().points,
                1e3 * last_step.mean_gap_after_m, 1e3 * last_step.max_gap_after_m);
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "vesica-register: %s\n", e.what());
    return 1;
  }
}
