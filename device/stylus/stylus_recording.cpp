#include "device/stylus/stylus_recording.h"

#include <array>
#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "device/input/input_recording.h"

namespace vesica::device {
namespace {

constexpr int kColumns = 9;
constexpr std::array<const char*, kColumns> kColumnNames = {"time_s", "x_m", "y_m",     "z_m",    "dx",
                                                            "dy",     "dz",  "button1", "button2"};

std::string FormatDouble(double v) {
  std::array<char, 32> buf{};
  const auto end = std::to_chars(buf.data(), buf.data() + buf.size(), v).ptr;
  return std::string(buf.data(), end);
}

std::string Shown(std::string_view s) {
  std::string out = "'";
  for (std::size_t i = 0; i < s.size() && i < 40; ++i) {
    const auto c = static_cast<unsigned char>(s[i]);
    out += (c >= 0x20 && c < 0x7f) ? static_cast<char>(c) : '?';
  }
  return out + (s.size() > 40 ? "...'" : "'");
}

std::string_view StripCr(std::string_view line) {
  return !line.empty() && line.back() == '\r' ? line.substr(0, line.size() - 1) : line;
}

}  // namespace

std::optional<std::string> StylusSampleProblem(const StylusSample& sample, const StylusSample* previous) {
  if (!std::isfinite(sample.time_s)) return "time_s is not finite";
  if (previous != nullptr && !(sample.time_s > previous->time_s)) return "time_s is not after the previous sample's";
  return StylusStateProblem(sample.state);
}

StylusRecording ParseStylusRecording(std::string_view text, const std::string& source_name) {
  StylusRecording rec;
  int number = 0;
  bool seen_header = false;
  std::optional<double> last_time;
  std::size_t pos = 0;
  while (pos < text.size()) {
    const std::size_t lf = text.find('\n', pos);
    const std::string_view line = StripCr(text.substr(pos, lf == std::string_view::npos ? lf : lf - pos));
    pos = lf == std::string_view::npos ? text.size() : lf + 1;
    ++number;
    if (number == 1) {
      if (line == kRecordingMagic) {
        throw RecordingError(source_name, 1, std::nullopt,
                             "this is a cholecystectomy input recording (two laparoscopic instruments), not a stylus "
                             "recording for the needle; a stylus recording starts with '" +
                                 std::string(kStylusRecordingMagic) + "'");
      }
      if (line != kStylusRecordingMagic) {
        throw RecordingError(source_name, 1, std::nullopt,
                             "not a stylus recording: line 1 is " + Shown(line) + ", expected '" +
                                 std::string(kStylusRecordingMagic) + "'");
      }
      continue;
    }
    if (!line.empty() && line.front() == '#') continue;
    if (!seen_header) {
      if (line != kStylusRecordingHeader) {
        throw RecordingError(source_name, number, std::nullopt,
                             "header is " + Shown(line) + ", expected '" + std::string(kStylusRecordingHeader) + "'");
      }
      seen_header = true;
      continue;
    }
    if (line.empty() && pos >= text.size()) break;
    std::array<double, kColumns> v{};
    std::string_view rest = line;
    for (int c = 0; c < kColumns; ++c) {
      const std::size_t comma = rest.find(',');
      const std::string_view field = rest.substr(0, comma);
      if (c < kColumns - 1 && comma == std::string_view::npos) {
        throw RecordingError(source_name, number, last_time,
                             "row has " + std::to_string(c + 1) + " fields, expected " + std::to_string(kColumns));
      }
      if (c == kColumns - 1 && comma != std::string_view::npos) {
        throw RecordingError(source_name, number, last_time,
                             "row has more than " + std::to_string(kColumns) + " fields");
      }
      const auto [end, ec] = std::from_chars(field.data(), field.data() + field.size(), v[c]);
      if (ec != std::errc{} || end != field.data() + field.size() || field.empty()) {
        throw RecordingError(source_name, number, last_time,
                             std::string(kColumnNames[c]) + " is " + Shown(field) + ", not a number");
      }
      rest = comma == std::string_view::npos ? std::string_view{} : rest.substr(comma + 1);
    }
    StylusSample s;
    s.time_s = v[0];
    s.state.p_BTip_B = {v[1], v[2], v[3]};
    s.state.d_B = {v[4], v[5], v[6]};
    for (int b = 0; b < 2; ++b) {
      if (v[7 + b] != 0.0 && v[7 + b] != 1.0) {
        throw RecordingError(source_name, number, v[0],
                             "button" + std::to_string(b + 1) + " is " + FormatDouble(v[7 + b]) + ", must be 0 or 1");
      }
    }
    s.state.buttons = (v[7] == 1.0 ? kStylusButton1 : 0u) | (v[8] == 1.0 ? kStylusButton2 : 0u);
    s.state.timestamp_ns = std::isfinite(v[0]) ? static_cast<std::int64_t>(std::llround(v[0] * 1e9)) : 0;
    if (auto problem = StylusSampleProblem(s, rec.samples.empty() ? nullptr : &rec.samples.back())) {
      throw RecordingError(source_name, number, std::isfinite(v[0]) ? std::optional<double>(v[0]) : last_time,
                           *problem);
    }
    s.state = NormalizedStylus(s.state);
    rec.samples.push_back(s);
    last_time = s.time_s;
  }
  if (!seen_header) throw RecordingError(source_name, number, std::nullopt, "ends before the header line");
  if (rec.samples.empty()) throw RecordingError(source_name, number, std::nullopt, "has no samples");
  return rec;
}

StylusRecording ReadStylusRecording(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw RecordingError(file.string(), 0, std::nullopt, "cannot open the file");
  std::ostringstream text;
  text << in.rdbuf();
  return ParseStylusRecording(text.str(), file.string());
}

std::string FormatStylusRecording(const StylusRecording& recording) {
  if (recording.samples.empty()) throw std::invalid_argument("stylus recording has no samples");
  std::string out = std::string(kStylusRecordingMagic) + "\n" + std::string(kStylusRecordingHeader) + "\n";
  for (std::size_t i = 0; i < recording.samples.size(); ++i) {
    const StylusSample& s = recording.samples[i];
    if (auto problem = StylusSampleProblem(s, i == 0 ? nullptr : &recording.samples[i - 1])) {
      throw std::invalid_argument("stylus recording sample " + std::to_string(i) + ": " + *problem);
    }
    out += FormatDouble(s.time_s);
    // Appended piece by piece (GCC 12 warns falsely on "literal" + std::string here).
    for (int k = 0; k < 3; ++k) out.append(",").append(FormatDouble(s.state.p_BTip_B[k]));
    for (int k = 0; k < 3; ++k) out.append(",").append(FormatDouble(s.state.d_B[k]));
    out += (s.state.buttons & kStylusButton1) ? ",1" : ",0";
    out += (s.state.buttons & kStylusButton2) ? ",1\n" : ",0\n";
  }
  return out;
}

void WriteStylusRecording(const std::filesystem::path& file, const StylusRecording& recording) {
  const std::string text = FormatStylusRecording(recording);
  std::ofstream out(file, std::ios::binary);
  if (!out || !out.write(text.data(), static_cast<std::streamsize>(text.size()))) {
    throw std::runtime_error("cannot write stylus recording " + file.string());
  }
}

}  // namespace vesica::device
