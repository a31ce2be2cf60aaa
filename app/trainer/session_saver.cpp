#include "app/trainer/session_saver.h"

#include <spdlog/spdlog.h>

#include <exception>
#include <utility>

#include "app/records/pending_sessions.h"
#include "app/records/session_store.h"

namespace vesica::app {
namespace {

bool IsValid(const SessionRecord& record) {
  try {
    ValidateRecord(record);
    return true;
  } catch (const RecordsError&) {
    return false;
  }
}

}  // namespace

SessionSaver::SessionSaver(std::string location, std::filesystem::path pending, SaverOptions options)
    : location_(std::move(location)), pending_(std::move(pending)), options_(options) {
  thread_ = std::thread([this] { Run(); });
}

SessionSaver::~SessionSaver() {
  Finish(true);
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  thread_.join();
}

std::uint64_t SessionSaver::Save(SessionRecord record) {
  std::uint64_t ticket = 0;
  {
    std::lock_guard lock(mutex_);
    ticket = next_ticket_++;
    queue_.emplace_back(ticket, std::move(record));
  }
  wake_.notify_all();
  return ticket;
}

bool SessionSaver::Busy() const {
  std::lock_guard lock(mutex_);
  return working_ || !queue_.empty();
}

std::vector<SaveResult> SessionSaver::TakeResults() {
  std::lock_guard lock(mutex_);
  return std::exchange(results_, {});
}

void SessionSaver::Finish(bool no_more_retries) {
  std::unique_lock lock(mutex_);
  if (no_more_retries) hurry_ = true;
  wake_.notify_all();  // cuts a retry wait short
  idle_.wait(lock, [this] { return !working_ && queue_.empty(); });
  hurry_ = false;
}

void SessionSaver::Run() {
  std::unique_lock lock(mutex_);
  while (true) {
    wake_.wait(lock, [this] { return stop_ || !queue_.empty(); });
    if (queue_.empty()) return;  // stop_ with nothing left
    auto [ticket, record] = std::move(queue_.front());
    queue_.pop_front();
    working_ = true;
    lock.unlock();
    SaveResult result = Store(ticket, record);
    lock.lock();
    results_.push_back(std::move(result));
    working_ = false;
    idle_.notify_all();
  }
}

SaveResult SessionSaver::Store(std::uint64_t ticket, const SessionRecord& record) {
  SaveResult result;
  result.ticket = ticket;
  std::string error;
  for (int attempt = 1; attempt <= options_.attempts; ++attempt) {
    try {
      result.id = OpenSessionStore(location_)->Add(record);
      result.message = "Session saved";
      return result;
    } catch (const std::exception& e) {
      error = e.what();
    }
    if (!IsValid(record)) break;  // a bad record does not get better by waiting
    std::unique_lock lock(mutex_);
    if (hurry_ || attempt == options_.attempts) break;
    spdlog::warn("saving the session, try {} of {}: {}; trying again", attempt, options_.attempts, error);
    wake_.wait_for(lock, options_.retry_wait, [this] { return hurry_; });
  }
  try {
    KeepPendingSession(pending_, record);
    result.kept_pending = true;
    result.message = "Session NOT saved yet: " + error + ". It is kept in " + pending_.string() +
                     " and will be stored at the next start";
    spdlog::error("{}", result.message);
  } catch (const std::exception& e) {
    result.message = "Session could NOT be saved: " + error + "; nor kept: " + e.what();
    spdlog::error("{}", result.message);
  }
  return result;
}

}  // namespace vesica::app
