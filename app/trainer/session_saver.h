#pragma once
// Stores finished sessions off the GUI thread. A database that is locked (another station, the
// records tool) or briefly unreachable is retried; a session that still cannot be stored is kept
// in the pending file (pending_sessions.h) and stored at the next start. The window polls
// TakeResults() on its timer and shows "saving..." while Busy(). No Qt: plain threads.

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <filesystem>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "app/records/session_record.h"

namespace vesica::app {

struct SaverOptions {
  int attempts = 4;                                      ///< tries before the pending file (>= 1)
  std::chrono::milliseconds retry_wait{1000};            ///< between tries (each also waits SQLite's 5 s busy timeout)
};

struct SaveResult {
  std::uint64_t ticket = 0;           ///< as Save() returned it
  std::optional<std::int64_t> id;     ///< the stored record's id
  bool kept_pending = false;          ///< not stored: waiting in the pending file
  std::string message;                ///< for the status bar: what happened (and why, on failure)
};

class SessionSaver {
 public:
  /// `location`: SessionStore location; `pending`: where sessions that cannot be stored wait.
  SessionSaver(std::string location, std::filesystem::path pending, SaverOptions options = {});
  /// Finish(): every queued session is stored or kept pending before the thread ends.
  ~SessionSaver();
  SessionSaver(const SessionSaver&) = delete;
  SessionSaver& operator=(const SessionSaver&) = delete;

  /// Queues `record`; returns its ticket at once.
  std::uint64_t Save(SessionRecord record);
  /// True while a session is queued or being stored.
  bool Busy() const;
  /// Results that arrived since the last call, in ticket order.
  std::vector<SaveResult> TakeResults();
  /// Blocks until the queue is empty. With `no_more_retries` (the trainer is closing), a session
  /// that fails once goes to the pending file at once instead of being retried.
  void Finish(bool no_more_retries);

  const std::string& location() const { return location_; }
  const std::filesystem::path& pending_path() const { return pending_; }

 private:
  void Run();
  SaveResult Store(std::uint64_t ticket, const SessionRecord& record);

  const std::string location_;
  const std::filesystem::path pending_;
  const SaverOptions options_;
  mutable std::mutex mutex_;
  std::condition_variable wake_, idle_;
  std::deque<std::pair<std::uint64_t, SessionRecord>> queue_;
  std::vector<SaveResult> results_;
  std::uint64_t next_ticket_ = 1;
  bool working_ = false, hurry_ = false, stop_ = false;
  std::thread thread_;
};

}  // namespace vesica::app
