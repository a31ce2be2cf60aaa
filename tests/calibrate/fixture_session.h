// A technician's hands over UDP: vesica-armsim --fixture-control as a child whose standard input
// takes "reference-load on", "hand jaw=0.7" ... (each answered "ok ..."), and vesica-calibrate run
// interactively, its prompts on stderr answered on its standard input as they come.
#pragma once

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <functional>
#include <string>
#include <vector>

#include "tool_process.h"

namespace vesica::app::calibrate::testing {

class FixtureArmsim {
 public:
  bool Start(const std::string& path, std::vector<std::string> args) {
    args.insert(args.begin(), "--fixture-control");
    int in[2], out[2];
    if (pipe(in) != 0 || pipe(out) != 0) return false;
    posix_spawn_file_actions_t a;
    posix_spawn_file_actions_init(&a);
    posix_spawn_file_actions_adddup2(&a, in[0], STDIN_FILENO);
    posix_spawn_file_actions_adddup2(&a, out[1], STDOUT_FILENO);
    posix_spawn_file_actions_addclose(&a, in[1]);
    posix_spawn_file_actions_addclose(&a, out[0]);
    std::vector<std::string> all{path};
    all.insert(all.end(), args.begin(), args.end());
    std::vector<char*> argv;
    for (auto& s : all) argv.push_back(s.data());
    argv.push_back(nullptr);
    const int rc = posix_spawn(&pid_, path.c_str(), &a, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&a);
    close(in[0]);
    close(out[1]);
    in_ = in[1];
    out_ = out[0];
    return rc == 0;
  }
  /// Sends one command and waits (up to 5 s) for its "ok" answer; false on an error or no answer.
  bool Command(const std::string& line) {
    const std::string text = line + "\n";
    if (write(in_, text.data(), text.size()) != static_cast<ssize_t>(text.size())) return false;
    const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(5);
    while (std::chrono::steady_clock::now() < until) {
      if (out_text_.find("ok " + line + "\n") != std::string::npos) {
        out_text_.clear();
        return true;
      }
      if (out_text_.find("error " + line) != std::string::npos) return false;
      pollfd p{out_, POLLIN, 0};
      if (poll(&p, 1, 100) > 0) {
        char buf[1024];
        const ssize_t n = read(out_, buf, sizeof buf);
        if (n <= 0) return false;
        out_text_.append(buf, static_cast<std::size_t>(n));
      }
    }
    return false;
  }
  ~FixtureArmsim() {
    if (in_ >= 0) close(in_);
    if (pid_ > 0) {
      kill(pid_, SIGTERM);
      waitpid(pid_, nullptr, 0);
    }
    if (out_ >= 0) close(out_);
  }

 private:
  pid_t pid_ = -1;
  int in_ = -1, out_ = -1;
  std::string out_text_;
};

/// Runs vesica-calibrate with its stdin open: each whole stderr line goes to `answer`, and what it
/// returns (if anything) is written to the tool's standard input.
inline ToolRun RunToolAnswering(const std::vector<std::string>& args,
                                const std::function<std::string(const std::string& line)>& answer) {
  ToolRun r;
  const SpawnedTool t = SpawnTool(args);
  if (t.pid < 0) return r;
  pollfd fds[2] = {{t.out, POLLIN, 0}, {t.err, POLLIN, 0}};
  int open_fds = 2;
  std::string partial;
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
      if (k != 1) continue;
      partial.append(buf, static_cast<std::size_t>(n));
      for (auto end = partial.find('\n'); end != std::string::npos; end = partial.find('\n')) {
        const std::string reply = answer(partial.substr(0, end));
        partial.erase(0, end + 1);
        if (!reply.empty()) (void)!write(t.in, reply.data(), reply.size());
      }
    }
  }
  close(t.in);
  r.exit_code = WaitTool(t.pid);
  return r;
}

}  // namespace vesica::app::calibrate::testing
