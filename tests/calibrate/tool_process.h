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

/// vesica-calibrate started as a child, its standard input, output and error on pipes whose
/// parent ends are `in`, `out` and `err`; pid -1 (and no pipes) when it could not start.
struct SpawnedTool {
  pid_t pid = -1;
  int in = -1, out = -1, err = -1;
};

inline SpawnedTool SpawnTool(const std::vector<std::string>& args) {
  SpawnedTool t;
  int in[2], out[2], err[2];
  if (pipe(in) || pipe(out) || pipe(err)) return t;
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
  const int rc = posix_spawn(&t.pid, VESICA_CALIBRATE_PATH, &a, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&a);
  close(in[0]);
  close(out[1]);
  close(err[1]);
  if (rc != 0) {
    for (int fd : {in[1], out[0], err[0]}) close(fd);
    t.pid = -1;
    return t;
  }
  t.in = in[1];
  t.out = out[0];
  t.err = err[0];
  return t;
}

/// Waits for the child to end: its exit code, -1 if it did not exit normally.
inline int WaitTool(pid_t pid) {
  int status = 0;
  waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

inline ToolRun RunTool(const std::vector<std::string>& args, const std::string& stdin_text = "",
                       const std::string& interrupt_on = "") {
  ToolRun r;
  const SpawnedTool t = SpawnTool(args);
  if (t.pid < 0) return r;
  const pid_t pid = t.pid;
  if (!stdin_text.empty()) (void)!write(t.in, stdin_text.data(), stdin_text.size());
  close(t.in);
  pollfd fds[2] = {{t.out, POLLIN, 0}, {t.err, POLLIN, 0}};
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
  r.exit_code = WaitTool(pid);
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
