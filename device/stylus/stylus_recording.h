#pragma once
// The v1 text format of a recorded stylus stream (docs/omni.md): a magic line, optional comment
// lines, a fixed CSV header, one row per sample. Also the scripted hand of vesica-omnisim.
// Doubles are written shortest round-trip, so Format -> Parse gives back bit-identical samples.
// Errors are RecordingError ("SOURCE:LINE (t=T s): WHAT"), as for the instrument recordings.

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "device/input/recording_error.h"
#include "device/stylus/stylus_state.h"

namespace vesica::device {

inline constexpr std::string_view kStylusRecordingMagic = "# vesica stylus recording v1";
inline constexpr std::string_view kStylusRecordingHeader = "time_s,x_m,y_m,z_m,dx,dy,dz,button1,button2";

struct StylusSample {
  double time_s = 0;  ///< s, strictly increasing sample to sample
  StylusState state;  ///< d_B unit after parsing (any non-zero length is accepted and normalised)
};

struct StylusRecording {
  std::vector<StylusSample> samples;
};

/// What is wrong with `sample` after `previous` (nullptr: the first), or nullopt.
std::optional<std::string> StylusSampleProblem(const StylusSample& sample, const StylusSample* previous);

/// Parses a whole recording. Throws RecordingError naming source_name, the line and the time; a
/// cholecystectomy input recording (two laparoscopic instruments) is named as such.
StylusRecording ParseStylusRecording(std::string_view text, const std::string& source_name);
StylusRecording ReadStylusRecording(const std::filesystem::path& file);

/// The v1 text; std::invalid_argument for a recording the parser would reject.
std::string FormatStylusRecording(const StylusRecording& recording);
void WriteStylusRecording(const std::filesystem::path& file, const StylusRecording& recording);

}  // namespace vesica::device
