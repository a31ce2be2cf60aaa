#pragma once
// Where a finished session's instrument input is saved: one new file per session in the
// recordings folder, never shared. Two sessions that start in the same second (R, then Enter;
// two stations on one folder) once wrote one file and lost one input.

#include <cstdint>
#include <filesystem>
#include <string>

namespace vesica::app {

/// The trainee id as one file-name component: characters other than letters, digits, '.', '-'
/// and '_' (a '/' above all) become '_'; an empty or dots-only id becomes "trainee".
std::string SafeFileNamePart(const std::string& text);

/// Creates a new, empty file "<trainee>-session-<started_unix_s>.csv" in `dir` (created if
/// missing), or "...-2.csv", "...-3.csv" when the name is taken (exclusive creation, so no two
/// sessions, in one process or two, get the same file), and returns its path. Throws
/// std::runtime_error naming the folder and the system's reason when it cannot.
std::filesystem::path CreateSessionRecordingFile(const std::filesystem::path& dir, const std::string& trainee_id,
                                                 std::int64_t started_unix_s);

}  // namespace vesica::app
