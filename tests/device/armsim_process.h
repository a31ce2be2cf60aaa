// Starts vesica-armsim as a child process on UDP loopback and collects its --report line.
#pragma once

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <memory>
#include <string>
#include <vector>

#include "firmware_protocol/transport/udp_transport.h"

extern char** environ;

namespace vesica::device::testing {

/// A free UDP port on loopback right now (bound and released; a small race is accepted).
inline std::uint16_t FreeUdpPort() {
  std::string error;
  auto probe = fp::UdpTransport::open({.local_port = 0}, error);
  return probe ? probe->local_port() : 0;
}

/// A base port for the arm bridge (ArmBridgeOptions::udp_base_port) whose first two arms' four
/// ports are all free right now; 0 if none was found.
inline int FreeArmBasePort() {
  for (int tries = 0; tries < 20; ++tries) {
    const int base = FreeUdpPort();
    if (base == 0 || base + 3 > 65535 - 2 * 126) continue;
    bool all_free = true;
    for (int p = base + 1; p <= base + 3; ++p) {
      std::string error;
      all_free = all_free && fp::UdpTransport::open({.local_port = static_cast<std::uint16_t>(p)}, error) != nullptr;
    }
    if (all_free) return base;
  }
  return 0;
}

class ArmsimProcess {
 public:
  /// Runs `path` with `args`; its stdout goes to a pipe read by Finish().
  bool Start(const std::string& path, const std::vector<std::string>& args) {
    int fds[2];
    if (pipe(fds) != 0) return false;
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_adddup2(&actions, fds[1], STDOUT_FILENO);
    posix_spawn_file_actions_addclose(&actions, fds[0]);
    std::vector<std::string> all{path};
    all.insert(all.end(), args.begin(), args.end());
    std::vector<char*> argv;
    for (auto& a : all) argv.push_back(a.data());
    argv.push_back(nullptr);
    const int rc = posix_spawn(&pid_, path.c_str(), &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    close(fds[1]);
    out_fd_ = fds[0];
    return rc == 0;
  }

  /// Sends `signal` to the child (SIGKILL: the arm's process dies as in a crash).
  void Kill(int signal) {
    if (pid_ > 0) kill(pid_, signal);
  }

  /// Waits for the child to exit; returns its exit status (-1 if killed) and its stdout.
  int Finish(std::string* stdout_text) {
    std::string text;
    char buf[4096];
    ssize_t n;
    while ((n = read(out_fd_, buf, sizeof buf)) > 0) text.append(buf, static_cast<std::size_t>(n));
    close(out_fd_);
    out_fd_ = -1;
    int status = 0;
    waitpid(pid_, &status, 0);
    pid_ = -1;
    if (stdout_text) *stdout_text = text;
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }

  ~ArmsimProcess() {
    if (pid_ > 0) {
      kill(pid_, SIGTERM);
      waitpid(pid_, nullptr, 0);
    }
    if (out_fd_ >= 0) close(out_fd_);
  }

 private:
  pid_t pid_ = -1;
  int out_fd_ = -1;
};

}  // namespace vesica::device::testing
