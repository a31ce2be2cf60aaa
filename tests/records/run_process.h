#pragma once
// Runs a program as a child process, as a user would from a shell, and collects what it wrote.

#include <map>
#include <optional>
#include <string>
#include <vector>

namespace vesica::app::testing {

struct ProcessResult {
  int exit_code = -1;  // -1 when killed by a signal
  std::string out;     // standard output
  std::string err;     // standard error
};

/// Runs argv[0] (a path) with the arguments; `env` sets (value) or unsets (nullopt) variables
/// in the child only. Standard input is /dev/null. `run_as_uid` >= 0: the child drops to that
/// user and group id before it starts (as root, to see what an unprivileged user sees: root
/// ignores file permissions). Throws std::runtime_error when it cannot start or does not finish
/// within `timeout_s`.
ProcessResult RunProcess(const std::vector<std::string>& argv,
                         const std::map<std::string, std::optional<std::string>>& env = {}, int timeout_s = 30,
                         int run_as_uid = -1);

/// The user id of "nobody" (65534 on Debian).
inline constexpr int kNobodyUid = 65534;

}  // namespace vesica::app::testing
