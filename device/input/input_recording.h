#pragma once
// The v1 text format of a recorded input session (docs/recording.md): a magic line, optional
// "# scenario: NAME", a fixed CSV header, one row per frame. Doubles are written shortest
// round-trip, so Format -> Parse gives back bit-identical frames.

#include <filesystem>
#include <string>
#include <string_view>

#include "device/input/input_frame.h"
#include "device/input/recording_error.h"

namespace vesica::device {

inline constexpr std::string_view kRecordingMagic = "# vesica input recording v1";
inline constexpr std::string_view kRecordingHeader =
    "time_s,left_yaw_rad,left_pitch_rad,left_roll_rad,left_insertion_m,left_jaw_rad,left_pedal,"
    "right_yaw_rad,right_pitch_rad,right_roll_rad,right_insertion_m,right_jaw_rad,right_pedal";

/// Parses a whole recording. Throws RecordingError naming source_name, the line and the time
/// for anything malformed (including a file cut short); never crashes on any byte sequence.
InputRecording ParseInputRecording(std::string_view text, const std::string& source_name);

/// Reads and parses `file`; an unreadable file throws RecordingError naming the path.
InputRecording ReadInputRecording(const std::filesystem::path& file);

/// The v1 text of `rec`. Throws std::invalid_argument for a recording the reader would reject
/// (no frames, a FrameProblem, a line break in the scenario name).
std::string FormatInputRecording(const InputRecording& rec);

/// Writes FormatInputRecording(rec) to `file`; throws std::runtime_error when it cannot.
void WriteInputRecording(const std::filesystem::path& file, const InputRecording& rec);

}  // namespace vesica::device
