#include "device/input/input_recording.h"

#include <algorithm>
#include <array>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <optional>
#include <stdexcept>
#include <system_error>

namespace vesica::device {
namespace {

constexpr int kColumnsV1 = 13;
constexpr int kColumns = 14;  // v2; v1 lacks the last
constexpr std::string_view kScenarioPrefix = "# scenario: ";
// A full dissection at 1 kHz is well under 100 MB; anything far beyond is not a recording.
constexpr std::uintmax_t kMaxFileBytes = std::uintmax_t{1} << 30;

constexpr std::array<std::string_view, kColumns> SplitHeader() {
  std::array<std::string_view, kColumns> names{};
  std::string_view rest = kRecordingHeaderV2;
  for (int i = 0; i < kColumns; ++i) {
    const std::size_t comma = rest.find(',');
    names[i] = rest.substr(0, comma);
    rest = comma == std::string_view::npos ? std::string_view{} : rest.substr(comma + 1);
  }
  return names;
}
constexpr std::array<std::string_view, kColumns> kColumnNames = SplitHeader();

// Shows a piece of untrusted input in a message: at most 40 bytes, control and non-ASCII bytes
// escaped, so a binary file gives a readable one-line error.
std::string Quote(std::string_view s) {
  std::string out = "'";
  const std::size_t shown = std::min<std::size_t>(s.size(), 40);
  for (std::size_t i = 0; i < shown; ++i) {
    const auto c = static_cast<unsigned char>(s[i]);
    if (c >= 0x20 && c < 0x7f && c != '\\' && c != '\'') {
      out += static_cast<char>(c);
    } else {
      static constexpr char kHex[] = "0123456789abcdef";
      out += "\\x";
      out += kHex[c >> 4];
      out += kHex[c & 0xf];
    }
  }
  if (shown < s.size()) out += "...";
  return out + "'";
}

std::string FormatDouble(double v) {
  std::array<char, 32> buf{};
  const auto end = std::to_chars(buf.data(), buf.data() + buf.size(), v).ptr;
  return std::string(buf.data(), end);
}

struct Line {
  std::string_view text;  // without the line break (LF or CRLF)
  bool terminated = false;
  int number = 0;         // 1-based
};

class LineReader {
 public:
  explicit LineReader(std::string_view text) : rest_(text) {}
  std::optional<Line> Next() {
    if (rest_.empty()) return std::nullopt;
    Line line;
    line.number = ++number_;
    const std::size_t lf = rest_.find('\n');
    if (lf == std::string_view::npos) {
      line.text = rest_;
      rest_ = {};
    } else {
      line.text = rest_.substr(0, lf);
      line.terminated = true;
      rest_ = rest_.substr(lf + 1);
    }
    if (!line.text.empty() && line.text.back() == '\r') line.text.remove_suffix(1);
    return line;
  }
  int number() const { return number_; }

 private:
  std::string_view rest_;
  int number_ = 0;
};

// Strict number: the whole field, no spaces or '+', finite. Returns what is wrong, if anything.
std::optional<std::string> ParseFinite(std::string_view field, double& out) {
  if (field.empty()) return "is empty";
  const auto [ptr, ec] = std::from_chars(field.data(), field.data() + field.size(), out);
  if (ec == std::errc::result_out_of_range) return Quote(field) + " is out of range";
  if (ec != std::errc{} || ptr != field.data() + field.size()) return Quote(field) + " is not a number";
  if (!std::isfinite(out)) return Quote(field) + " is not finite";
  return std::nullopt;
}

class Parser {
 public:
  Parser(std::string_view text, const std::string& source_name) : lines_(text), source_(source_name) {}

  InputRecording Run() {
    InputRecording rec;
    ReadMagic();
    const Line header = ReadCommentsAndHeader(rec);
    while (const std::optional<Line> line = lines_.Next()) rec.frames.push_back(ReadRow(*line));
    if (rec.frames.empty()) Fail(header.number, std::nullopt, "no frames after the header");
    return rec;
  }

 private:
  [[noreturn]] void Fail(int line, std::optional<double> time_s, const std::string& what) const {
    throw RecordingError(source_, line, time_s, what);
  }

  void RequireTerminated(const Line& line, std::optional<double> time_s) const {
    if (!line.terminated) Fail(line.number, time_s, "no newline at the end of this line: file truncated" + LastGood());
  }

  std::string LastGood() const {
    if (!last_good_line_) return "; no good row before it";
    return "; last good row: line " + std::to_string(last_good_line_) + ", t=" + FormatDouble(*last_good_time_s_) + " s";
  }

  void ReadMagic() {
    const std::optional<Line> line = lines_.Next();
    if (!line) Fail(1, std::nullopt, "empty file, expected " + Quote(kRecordingMagic));
    if (line->text == kRecordingMagicV2) columns_ = kColumns;
    if (line->text != kRecordingMagic && line->text != kRecordingMagicV2) {
      constexpr std::string_view kFamily = "# vesica input recording v";
      if (line->text.substr(0, kFamily.size()) == kFamily) {
        Fail(1, std::nullopt, "unsupported recording version " + Quote(line->text.substr(kFamily.size() - 1)) +
                                  ", this build reads v1 and v2");
      }
      Fail(1, std::nullopt, "not an input recording: line 1 is " + Quote(line->text) + ", expected " +
                                Quote(kRecordingMagic));
    }
    RequireTerminated(*line, std::nullopt);
  }

  Line ReadCommentsAndHeader(InputRecording& rec) {
    bool have_scenario = false;
    for (;;) {
      const std::optional<Line> line = lines_.Next();
      if (!line) Fail(lines_.number() + 1, std::nullopt, "missing header line " + Quote(Header()));
      if (line->text.substr(0, 1) == "#") {
        if (line->text.substr(0, kScenarioPrefix.size()) == kScenarioPrefix) {
          if (have_scenario) Fail(line->number, std::nullopt, "second '# scenario:' line");
          rec.scenario_name = std::string(line->text.substr(kScenarioPrefix.size()));
          have_scenario = true;
        }
        RequireTerminated(*line, std::nullopt);
        continue;
      }
      CheckHeader(*line);
      RequireTerminated(*line, std::nullopt);
      return *line;
    }
  }

  void CheckHeader(const Line& line) const {
    std::string_view rest = line.text;
    for (int column = 0;; ++column) {
      const std::size_t comma = rest.find(',');
      const std::string_view name = rest.substr(0, comma);
      if (column >= columns_) {
        Fail(line.number, std::nullopt, "header has an extra column " + std::to_string(column + 1) + " " + Quote(name) +
                                            " after " + Quote(kColumnNames[columns_ - 1]));
      }
      if (name != kColumnNames[column]) {
        Fail(line.number, std::nullopt, "header column " + std::to_string(column + 1) + " is " + Quote(name) +
                                            ", expected " + Quote(kColumnNames[column]));
      }
      if (comma == std::string_view::npos) {
        if (column + 1 < columns_) {
          Fail(line.number, std::nullopt, "header ends after column " + std::to_string(column + 1) + ", expected " +
                                              Quote(kColumnNames[column + 1]) + " next");
        }
        return;
      }
      rest = rest.substr(comma + 1);
    }
  }

  InputFrame ReadRow(const Line& line) {
    const std::size_t count = static_cast<std::size_t>(std::count(line.text.begin(), line.text.end(), ',')) + 1;
    std::array<std::string_view, kColumns> fields{};
    std::string_view rest = line.text;
    const auto columns = static_cast<std::size_t>(columns_);
    for (std::size_t i = 0; i < std::min(count, columns); ++i) {
      const std::size_t comma = rest.find(',');
      fields[i] = rest.substr(0, comma);
      rest = comma == std::string_view::npos ? std::string_view{} : rest.substr(comma + 1);
    }

    // The row's own time when it reads as one; otherwise the last good row's.
    InputFrame frame;
    const bool time_ok = !ParseFinite(fields[0], frame.time_s).has_value();
    const std::optional<double> at = time_ok ? std::optional<double>(frame.time_s) : last_good_time_s_;

    if (count != columns) {
      Fail(line.number, at, "row has " + std::to_string(count) + " field" + (count == 1 ? "" : "s") + ", expected " +
                                std::to_string(columns) + (count < columns ? " (file truncated?)" : "") + LastGood());
    }
    RequireTerminated(line, last_good_time_s_);
    if (const auto problem = ParseFinite(fields[0], frame.time_s)) Fail(line.number, at, "time_s " + *problem);
    if (last_good_time_s_ && !(frame.time_s > *last_good_time_s_)) {
      Fail(line.number, at, "time_s " + FormatDouble(frame.time_s) + " is not after the previous row's " +
                                FormatDouble(*last_good_time_s_) + " (line " + std::to_string(last_good_line_) + ")");
    }
    for (int side = 0; side < 2; ++side) {
      const int base = 1 + 6 * side;
      physics::InstrumentPose& pose = frame.instruments[side].pose;
      double* const values[5] = {&pose.yaw_rad, &pose.pitch_rad, &pose.roll_rad, &pose.insertion_m,
                                 &pose.jaw_angle_rad};
      for (int k = 0; k < 5; ++k) {
        if (const auto problem = ParseFinite(fields[base + k], *values[k])) {
          Fail(line.number, at, std::string(kColumnNames[base + k]) + " " + *problem);
        }
      }
      if (pose.insertion_m < 0) {
        Fail(line.number, at, std::string(kColumnNames[base + 3]) + " is negative (" + Quote(fields[base + 3]) + ")");
      }
      const std::string_view pedal = fields[base + 5];
      if (pedal != "0" && pedal != "1") {
        Fail(line.number, at, std::string(kColumnNames[base + 5]) + " must be 0 or 1, found " + Quote(pedal));
      }
      frame.instruments[side].pedal = pedal == "1";
    }
    if (columns_ == kColumns) {
      const std::string_view key = fields[kColumns - 1];
      const std::optional<physics::InstrumentTool> tool = physics::ParseToolKey(key);
      if (!tool || !physics::IsRightHandTool(*tool)) {
        Fail(line.number, at, "right_tool must be cautery_hook, clip_applier or scissors, found " + Quote(key));
      }
      frame.right_tool = *tool;
    }
    last_good_line_ = line.number;
    last_good_time_s_ = frame.time_s;
    return frame;
  }

  std::string_view Header() const { return columns_ == kColumns ? kRecordingHeaderV2 : kRecordingHeader; }

  LineReader lines_;
  const std::string& source_;
  int columns_ = kColumnsV1;  // set by the magic line
  int last_good_line_ = 0;
  std::optional<double> last_good_time_s_;
};

}  // namespace

InputRecording ParseInputRecording(std::string_view text, const std::string& source_name) {
  return Parser(text, source_name).Run();
}

InputRecording ReadInputRecording(const std::filesystem::path& file) {
  const std::string name = file.string();
  std::error_code ec;
  if (std::filesystem::is_directory(file, ec)) throw RecordingError(name, 0, std::nullopt, "is a directory, not a recording");
  std::ifstream in(file, std::ios::binary);
  if (!in) throw RecordingError(name, 0, std::nullopt, std::string("cannot open input recording: ") + std::strerror(errno));
  std::string text;
  std::array<char, 1 << 16> chunk{};
  while (in) {
    in.read(chunk.data(), chunk.size());
    text.append(chunk.data(), static_cast<std::size_t>(in.gcount()));
    if (text.size() > kMaxFileBytes) throw RecordingError(name, 0, std::nullopt, "larger than 1 GiB, not a recording");
  }
  if (in.bad()) throw RecordingError(name, 0, std::nullopt, "read error");
  return ParseInputRecording(text, name);
}

std::string FormatInputRecording(const InputRecording& rec) {
  if (rec.scenario_name.find_first_of("\r\n") != std::string::npos) {
    throw std::invalid_argument("input recording: scenario name contains a line break");
  }
  if (rec.frames.empty()) throw std::invalid_argument("input recording: no frames");
  const bool exchanged = std::any_of(rec.frames.begin(), rec.frames.end(), [](const InputFrame& f) {
    return f.right_tool != physics::InstrumentTool::kCauteryHook;
  });
  std::string out;
  out.reserve(64 + rec.frames.size() * 200);
  out.append(exchanged ? kRecordingMagicV2 : kRecordingMagic).append("\n");
  if (!rec.scenario_name.empty()) out.append(kScenarioPrefix).append(rec.scenario_name).append("\n");
  out.append(exchanged ? kRecordingHeaderV2 : kRecordingHeader).append("\n");
  std::array<char, 32> buf{};
  const auto put = [&](double v) { out.append(buf.data(), std::to_chars(buf.data(), buf.data() + buf.size(), v).ptr); };
  for (std::size_t i = 0; i < rec.frames.size(); ++i) {
    const InputFrame& f = rec.frames[i];
    if (const auto problem = FrameProblem(f, i == 0 ? nullptr : &rec.frames[i - 1])) {
      throw std::invalid_argument("input recording: frame " + std::to_string(i) + ": " + *problem);
    }
    put(f.time_s);
    for (const InstrumentInput& in : f.instruments) {
      for (double v : {in.pose.yaw_rad, in.pose.pitch_rad, in.pose.roll_rad, in.pose.insertion_m, in.pose.jaw_angle_rad}) {
        out += ',';
        put(v);
      }
      out += in.pedal ? ",1" : ",0";
    }
    if (exchanged) out.append(",").append(physics::ToolKey(f.right_tool));
    out += '\n';
  }
  return out;
}

void WriteInputRecording(const std::filesystem::path& file, const InputRecording& rec) {
  const std::string text = FormatInputRecording(rec);
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  if (!out) throw std::runtime_error("cannot write input recording '" + file.string() + "': " + std::strerror(errno));
  out.write(text.data(), static_cast<std::streamsize>(text.size()));
  out.close();
  if (!out) throw std::runtime_error("cannot write input recording '" + file.string() + "': write failed");
}

}  // namespace vesica::device
