// "Finished sessions survive a kill -9 of the trainer": a child process writes sessions and is
// killed with SIGKILL; the parent reopens the store and finds every session whose Add had
// returned, nothing half-written, and a database that passes its integrity check.

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <optional>
#include <sstream>
#include <string>

#include "app/records/session_store.h"
#include "tests/records/sample_records.h"
#include "tests/records/store_test_fixture.h"

namespace vesica::app {
namespace {

std::string FileBytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

using ::testing::ElementsAre;
using testing::SampleRecord;
using testing::StoreTest;

// Its own suite name, so its instantiation does not repeat session_store_test.cpp's tests.
class StoreKillTest : public StoreTest {};

constexpr auto kReadTimeout = std::chrono::seconds(20);

// A forked child that reports progress one line at a time through a pipe.
class ReportingChild {
 public:
  // Runs `body` in a child process; it reports with Report(fd, line). The child ends with
  // _exit, never returning into GoogleTest or running the parent's static destructors (the
  // shared PostgreSQL server would be stopped).
  explicit ReportingChild(const std::function<void(int report_fd)>& body) {
    int fds[2];
    if (pipe(fds) != 0) throw std::runtime_error(std::string("pipe: ") + std::strerror(errno));
    pid_ = fork();
    if (pid_ < 0) throw std::runtime_error(std::string("fork: ") + std::strerror(errno));
    if (pid_ == 0) {
      close(fds[0]);
      try {
        body(fds[1]);
      } catch (const std::exception& error) {
        Report(fds[1], std::string("error ") + error.what());
        _exit(3);
      }
      _exit(0);
    }
    close(fds[1]);
    read_fd_ = fds[0];
  }

  ~ReportingChild() {
    if (pid_ > 0 && !reaped_) {
      kill(pid_, SIGKILL);
      waitpid(pid_, nullptr, 0);
    }
    if (read_fd_ >= 0) close(read_fd_);
  }

  static void Report(int fd, const std::string& line) {
    const std::string text = line + "\n";
    if (write(fd, text.data(), text.size()) != static_cast<ssize_t>(text.size())) _exit(4);
  }

  // The next line, or nullopt at end of stream; throws after kReadTimeout without one.
  std::optional<std::string> ReadLine() {
    const auto deadline = std::chrono::steady_clock::now() + kReadTimeout;
    while (true) {
      if (const auto end = buffer_.find('\n'); end != std::string::npos) {
        std::string line = buffer_.substr(0, end);
        buffer_.erase(0, end + 1);
        if (line.starts_with("error ")) throw std::runtime_error("child failed: " + line.substr(6));
        return line;
      }
      const auto left =
          std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
      if (left.count() <= 0) throw std::runtime_error("child reported nothing for 20 s");
      pollfd ready{read_fd_, POLLIN, 0};
      if (poll(&ready, 1, static_cast<int>(left.count())) < 0 && errno != EINTR) throw std::runtime_error("poll");
      char chunk[4096];
      const ssize_t n = read(read_fd_, chunk, sizeof chunk);
      if (n == 0) return std::nullopt;
      if (n > 0) buffer_.append(chunk, static_cast<std::size_t>(n));
    }
  }

  // kill -9, then waits for it; true when the signal is what ended it.
  bool KillNine() {
    kill(pid_, SIGKILL);
    int status = 0;
    while (waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
    }
    reaped_ = true;
    return WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL;
  }

 private:
  pid_t pid_ = -1;
  int read_fd_ = -1;
  bool reaped_ = false;
  std::string buffer_;
};

struct Added {
  int index;
  std::int64_t id;
};

Added ParseAdded(const std::string& line) {
  std::istringstream in(line);
  std::string word;
  Added added{};
  if (!(in >> word >> added.index >> added.id) || word != "added") throw std::runtime_error("bad line: " + line);
  return added;
}

TEST_P(StoreKillTest, KillNineDuringAddLoopLosesNoFinishedSession) {
  const std::string location = backend_.NewLocation();
  OpenSessionStore(location);  // schema in place, so the child does nothing but add
  constexpr int kFinishedBeforeKill = 25;

  ReportingChild child([&](int report_fd) {
    const auto store = OpenSessionStore(location);
    for (int i = 0;; ++i) {
      const std::int64_t id = store->Add(SampleRecord(i));
      ReportingChild::Report(report_fd, "added " + std::to_string(i) + " " + std::to_string(id));
    }
  });
  std::vector<Added> reported;
  while (static_cast<int>(reported.size()) < kFinishedBeforeKill) {
    const auto line = child.ReadLine();
    ASSERT_TRUE(line.has_value()) << "child ended after " << reported.size() << " sessions";
    reported.push_back(ParseAdded(*line));
  }
  // The child is inside its next Add now.
  ASSERT_TRUE(child.KillNine());
  while (const auto line = child.ReadLine()) reported.push_back(ParseAdded(*line));

  const auto store = OpenSessionStore(location);
  EXPECT_EQ(store->CheckIntegrity(), "ok");
  for (const auto& added : reported) {
    const auto stored = store->Get(added.id);
    ASSERT_TRUE(stored.has_value()) << "session " << added.index << " (id " << added.id << ") was lost";
    EXPECT_EQ(stored->record, SampleRecord(added.index));
  }
  // At most the session in flight got in besides, and it is whole.
  const auto sessions = store->List("trainee-7");
  ASSERT_GE(sessions.size(), reported.size());
  ASSERT_LE(sessions.size(), reported.size() + 1);
  for (std::size_t i = 0; i < sessions.size(); ++i) {
    EXPECT_EQ(sessions[i].record, SampleRecord(static_cast<int>(i))) << "session " << i;
  }
  // And the store still takes new sessions.
  const std::int64_t next = store->Add(SampleRecord(1000));
  EXPECT_EQ(store->Get(next)->record, SampleRecord(1000));
}

TEST_P(StoreKillTest, KillNineInsideOpenTransactionRollsItBack) {
  const std::string location = backend_.NewLocation();
  constexpr int kFinished = 10;
  const std::filesystem::path wal = location + "-wal";  // SQLite only
  // The WAL as the finished sessions left it, copied by the child before it starts the open
  // transaction (read by the parent after "finished", it could already hold some of its pages).
  const std::filesystem::path wal_committed = location + "-wal-committed";

  ReportingChild child([&](int report_fd) {
    const auto store = OpenSessionStore(location);
    for (int i = 0; i < kFinished; ++i) store->Add(SampleRecord(i));
    if (backend_.name() == "sqlite") std::filesystem::copy_file(wal, wal_committed);
    ReportingChild::Report(report_fd, "finished");
    backend_.StartUncommittedWrite(location);
    ReportingChild::Report(report_fd, "uncommitted");
    while (true) pause();
  });
  ASSERT_EQ(child.ReadLine(), "finished");
  ASSERT_EQ(child.ReadLine(), "uncommitted");
  if (backend_.name() == "sqlite") {
    // The uncommitted pages are in the WAL file: recovery on reopen has to leave them out. They are
    // appended, or written over old frames when a checkpoint had copied those back and the WAL
    // restarted (then the file need not grow): count the bytes that are new or changed.
    const std::string before = FileBytes(wal_committed), after = FileBytes(wal);
    const std::size_t common = std::min(before.size(), after.size());
    std::size_t changed = after.size() - common;
    for (std::size_t i = 0; i < common; ++i) changed += before[i] != after[i];
    EXPECT_GT(changed, 100u * 1024u) << "WAL " << before.size() << " -> " << after.size() << " bytes";
  }
  ASSERT_TRUE(child.KillNine());

  const auto store = OpenSessionStore(location);
  EXPECT_EQ(store->CheckIntegrity(), "ok");
  EXPECT_THAT(store->ListTrainees(), ElementsAre("trainee-7"));  // no ghosts
  const auto sessions = store->List("trainee-7");
  ASSERT_EQ(sessions.size(), static_cast<std::size_t>(kFinished));
  for (int i = 0; i < kFinished; ++i) EXPECT_EQ(sessions[i].record, SampleRecord(i)) << "session " << i;
}

INSTANTIATE_TEST_SUITE_P(Backends, StoreKillTest, ::testing::Values("sqlite", "postgres"), testing::BackendName);

}  // namespace
}  // namespace vesica::app
