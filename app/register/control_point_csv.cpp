#include "app/register/control_point_csv.h"

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

namespace vesica::app::registration {

namespace {
std::string Trim(const std::string& s) {
  const auto begin = s.find_first_not_of(" \t\r");
  if (begin == std::string::npos) return "";
  return s.substr(begin, s.find_last_not_of(" \t\r") - begin + 1);
}

[[noreturn]] void Fail(const std::filesystem::path& file, int line, const std::string& what) {
  throw RegisterInputError(file.string() + ":" + std::to_string(line) + ": " + what);
}

double ParseNumber(const std::string& field, const char* name, const std::filesystem::path& file, int line) {
  std::size_t used = 0;
  double value = 0.0;
  try {
    value = std::stod(field, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != field.size()) Fail(file, line, std::string(name) + " '" + field + "' is not a number");
  if (!std::isfinite(value)) Fail(file, line, std::string(name) + " is not finite (" + field + ")");
  return value;
}

int ParseInteger(const std::string& field, const char* name, const std::filesystem::path& file, int line) {
  const double value = ParseNumber(field, name, file, line);
  if (value != std::floor(value) || std::abs(value) > 1e9)
    Fail(file, line, std::string(name) + " '" + field + "' is not an integer");
  return static_cast<int>(value);
}
}  // namespace

ControlPointSeries ReadControlPointCsv(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw RegisterInputError(file.string() + ": cannot be opened");
  ControlPointSeries series;
  std::string text;
  int line = 0;
  bool header_seen = false;
  while (std::getline(in, text)) {
    ++line;
    const std::string row = Trim(text);
    if (row.empty() || row[0] == '#') continue;
    if (!header_seen) {
      if (row != kControlPointCsvHeader)
        Fail(file, line, "expected the header '" + std::string(kControlPointCsvHeader) + "', found '" + row + "'");
      header_seen = true;
      continue;
    }
    std::vector<std::string> fields;
    std::stringstream split(row);
    for (std::string f; std::getline(split, f, ',');) fields.push_back(Trim(f));
    if (fields.size() != 10) Fail(file, line, "expected 10 fields, found " + std::to_string(fields.size()));
    const int frame = ParseInteger(fields[0], "frame", file, line);
    const double time_s = ParseNumber(fields[1], "time_s", file, line);
    physics::ControlPoint p;
    p.p_W = {ParseNumber(fields[2], "x_m", file, line), ParseNumber(fields[3], "y_m", file, line),
             ParseNumber(fields[4], "z_m", file, line)};
    const Eigen::Vector3d n(ParseNumber(fields[5], "nx", file, line), ParseNumber(fields[6], "ny", file, line),
                            ParseNumber(fields[7], "nz", file, line));
    if (!(n.norm() > 1e-12)) Fail(file, line, "the normal (nx, ny, nz) has zero length");
    p.inward_normal_W = n.normalized();
    p.confidence = ParseNumber(fields[8], "confidence", file, line);
    if (!(p.confidence > 0.0 && p.confidence <= 1.0))
      Fail(file, line, "confidence " + fields[8] + " is outside (0, 1]");
    p.plane = ParseInteger(fields[9], "plane", file, line);
    if (series.frames.empty() || series.frames.back().frame != frame) {
      if (!series.frames.empty()) {
        const physics::ControlFrame& last = series.frames.back();
        if (frame < last.frame)
          Fail(file, line,
               "frame " + std::to_string(frame) + " after frame " + std::to_string(last.frame) +
                   ": frames out of order");
        if (!(time_s > last.time_s))
          Fail(file, line,
               "time " + fields[1] + " s of frame " + std::to_string(frame) + " is not after frame " +
                   std::to_string(last.frame) + "'s");
      }
      series.frames.push_back({frame, time_s, {}});
      series.lines.emplace_back();
    } else if (time_s != series.frames.back().time_s) {
      Fail(file, line, "time " + fields[1] + " s differs from the frame's first row's");
    }
    series.frames.back().points.push_back(p);
    series.lines.back().push_back(line);
  }
  if (!header_seen) throw RegisterInputError(file.string() + ": empty (no header line)");
  if (series.frames.empty()) throw RegisterInputError(file.string() + ": no control points");
  return series;
}

void CheckPointsNearSurface(const ControlPointSeries& series, const std::filesystem::path& file,
                            const physics::RegistrationSurface& surface, const physics::Vertices& x_W,
                            double max_distance_m) {
  const physics::PairingOptions any_side{false, 0.0, max_distance_m};
  for (size_t f = 0; f < series.frames.size(); ++f)
    for (size_t p = 0; p < series.frames[f].points.size(); ++p)
      if (!physics::PairControlPoint(surface, x_W, series.frames[f].points[p], any_side)) {
        std::ostringstream what;
        what << "the point is more than " << max_distance_m * 1e3 << " mm from the mesh's surface";
        Fail(file, series.lines[f][p], what.str());
      }
}

}  // namespace vesica::app::registration
