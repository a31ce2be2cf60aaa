#pragma once
// The text format of a recorded input session (docs/recording.md): a magic line, optional
// "# scenario: NAME", a fixed CSV header, one row per frame. Doubles are written shortest
// round-trip, so Format -> Parse gives back bit-identical frames. v2 adds the right port's tool
// (instrument exchange); a recording whose right port holds the hook throughout is written as v1,
// so recordings made before the exchange existed read and write back byte for byte.

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
inline constexpr std::string_view kRecordingMagicV2 = "# vesica input recording v2";
/// v1's columns and the right port's tool: cautery_hook, clip_applier or scissors.
inline constexpr std::string_view kRecordingHeaderV2 =
    "time_s,left_yaw_rad,left_pitch_rad,left_roll_rad,left_insertion_m,left_jaw_rad,left_pedal,"
    "right_yaw_rad,right_pitch_rad,right_roll_rad,right_insertion_m,right_jaw_rad,right_pedal,right_tool";

/// Parses a whole recording. Throws RecordingError naming source_name, the line and the time
/// for anything malformed (including a file cut short); never crashes on any byte sequence.
InputRecording ParseInputRecording(std::string_view text, const std::string& source_name);

/// Reads and parses `file`; an unreadable file throws RecordingError naming the path.
InputRecording ReadInputRecording(const std::filesystem::path& file);

/// The text of `rec`: v1 while the right port holds the hook in every frame, else v2. Throws std::invalid_argument for a recording the reader would reject
/// (no frames, a FrameProblem, a line break in the scenario name).
std::string FormatInputRecording(const InputRecording& rec);

/// Writes FormatInputRecording(rec) to `file`; throws std::runtime_error when it cannot.
void WriteInputRecording(const std::filesystem::path& file, const InputRecording& rec);

}  // namespace vesica::device
