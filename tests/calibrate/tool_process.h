// Runs the real vesica-calibrate as a child process: arguments, optional stdin text, stdout and
// stderr collected, and optionally SIGINT sent once a stderr line contains a given text (Ctrl-C
// in the middle of a step).
#pragma once

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

extern char** environ;

namespace vesica::app::calibrate::testing {

struct ToolRun {
  int exit_code = -1;
  std::string out, err;
  bool interrupted = false;  ///< SIGINT was sent
  nlohmann::json json() const { return nlohmann::json::parse(out); }
};

inline ToolRun RunTool(const std::vector<std::string>& args, const std::string& stdin_text = "",
                       const std::string& interrupt_on = "") {
  ToolRun r;
  int in[2], out[2], err[2];
  if (pipe(in) || pipe(out) || pipe(err)) return r;
  posix_spawn_file_actions_t a;
  posix_spawn_file_actions_init(&a);
  posix_spawn_file_actions_adddup2(&a, in[0], STDIN_FILENO);
  posix_spawn_file_actions_adddup2(&a, out[1], STDOUT_FILENO);
  posix_spawn_file_actions_adddup2(&a, err[1], STDERR_FILENO);
  for (int fd : {in[1], out[0], err[0]}) posix_spawn_file_actions_addclose(&a, fd);
  std::vector<std::string> all{VESICA_CALIBRATE_PATH};
  all.insert(all.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& s : all) argv.push_back(s.data());
  argv.push_back(nullptr);
  pid_t pid = -1;
  const int rc = posix_spawn(&pid, VESICA_CALIBRATE_PATH, &a, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&a);
  close(in[0]);
  close(out[1]);
  close(err[1]);
  if (rc != 0) return r;
  if (!stdin_text.empty()) (void)!write(in[1], stdin_text.data(), stdin_text.size());
  close(in[1]);
  pollfd fds[2] = {{out[0], POLLIN, 0}, {err[0], POLLIN, 0}};
  int open_fds = 2;
  char buf[4096];
  while (open_fds > 0) {
    if (poll(fds, 2, -1) < 0) break;
    for (int k = 0; k < 2; ++k) {
      if (fds[k].fd < 0 || !(fds[k].revents & (POLLIN | POLLHUP))) continue;
      const ssize_t n = read(fds[k].fd, buf, sizeof buf);
      if (n <= 0) {
        close(fds[k].fd);
        fds[k].fd = -1;
        --open_fds;
        continue;
      }
      (k == 0 ? r.out : r.err).append(buf, static_cast<std::size_t>(n));
      if (k == 1 && !interrupt_on.empty() && !r.interrupted && r.err.find(interrupt_on) != std::string::npos) {
        kill(pid, SIGINT);
        r.interrupted = true;
      }
    }
  }
  int status = 0;
  waitpid(pid, &status, 0);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

/// A fresh, empty folder in the system's temporary directory (never the working directory: a
/// test run from the repository root would leave its folders there), one per test process so
/// that parallel runs of several build directories do not share one. It and anything named after
/// it (d + "-corrupt.vcal") go when the test program ends.
inline std::string FreshDir(const std::string& name) {
  struct Removed {
    std::filesystem::path root =
        std::filesystem::temp_directory_path() / ("vesica-calibrate-test-" + std::to_string(getpid()));
    ~Removed() {
      std::error_code ignored;
      std::filesystem::remove_all(root, ignored);
    }
  };
  static const Removed removed;
  std::filesystem::create_directories(removed.root);
  const std::string d = (removed.root / name).string();
  std::filesystem::remove_all(d);
  return d;
}

inline std::vector<std::uint8_t> ReadBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// Every file under dir, relative names, sorted.
inline std::vector<std::string> FilesUnder(const std::string& dir) {
  std::vector<std::string> files;
  if (!std::filesystem::exists(dir)) return files;
  for (const auto& e : std::filesystem::recursive_directory_iterator(dir))
    if (e.is_regular_file()) files.push_back(std::filesystem::relative(e.path(), dir).string());
  std::sort(files.begin(), files.end());
  return files;
}

}  // namespace vesica::app::calibrate::testing
