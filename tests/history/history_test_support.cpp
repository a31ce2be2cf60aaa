#include "history_test_support.h"

#include <stdlib.h>

#include <stdexcept>
#include <string>

namespace vesica::app::testing {

TempDir::TempDir() {
  std::string pattern = (std::filesystem::temp_directory_path() / "vesica-history-XXXXXX").string();
  if (mkdtemp(pattern.data()) == nullptr) throw std::runtime_error("mkdtemp failed");
  path_ = pattern;
}

TempDir::~TempDir() {
  std::error_code ignored;
  std::filesystem::remove_all(path_, ignored);
}

namespace {

SessionRecord Record(const std::string& trainee, std::int64_t start, double duration_s) {
  SessionRecord r;
  r.trainee_id = trainee;
  r.scenario = "cholecystectomy-default";
  r.station = "station-1";
  r.started_unix_s = start;
  r.ended_unix_s = start + static_cast<std::int64_t>(duration_s) + 30;
  r.metrics.duration_s = duration_s;
  return r;
}

}  // namespace

std::vector<SessionRecord> AnaSessions() {
  // 2026-11-23T03:20:00Z, then a day apart each.
  SessionRecord a = Record("ana", 1795404000, 900.0);
  a.metrics.path_length_left_m = 3.25;
  a.metrics.path_length_right_m = 2.5;
  a.metrics.slips = 7;
  a.metrics.cautery_on_s = 95.5;
  a.metrics.liver_damage_m2 = 4.0e-5;
  a.metrics.gallbladder_damage_m2 = 1.5e-5;
  a.metrics.max_force_N = 6.75;
  a.metrics.mean_force_N = 2.25;
  a.metrics.tissue_removed_fraction = 0.625;
  a.metrics.springs_cut = 70;
  a.metrics.springs_total = 86;
  a.metrics.perforation = true;
  a.metrics.gallbladder_free = false;
  a.metrics.success = false;

  SessionRecord b = Record("ana", 1795404000 + 86400, 720.0);
  b.metrics.path_length_left_m = 2.75;
  b.metrics.path_length_right_m = 2.0;
  b.metrics.slips = 4;
  b.metrics.cautery_on_s = 80.25;
  b.metrics.liver_damage_m2 = 2.5e-5;
  b.metrics.max_force_N = 5.5;
  b.metrics.mean_force_N = 2.0;
  b.metrics.tissue_removed_fraction = 0.75;
  b.metrics.springs_cut = 86;
  b.metrics.springs_total = 86;
  b.metrics.gallbladder_free = true;
  b.metrics.perforation = true;
  b.metrics.success = false;

  SessionRecord c = Record("ana", 1795404000 + 2 * 86400, 480.5);
  c.metrics.path_length_left_m = 1.5;
  c.metrics.path_length_right_m = 1.25;
  c.metrics.slips = 1;
  c.metrics.cautery_on_s = 60.0;
  c.metrics.liver_damage_m2 = 5.0e-6;
  c.metrics.max_force_N = 4.25;
  c.metrics.mean_force_N = 1.5;
  c.metrics.tissue_removed_fraction = 0.875;
  c.metrics.springs_cut = 86;
  c.metrics.springs_total = 86;
  c.metrics.gallbladder_free = true;
  c.metrics.success = true;
  c.input_recording_path = "/recordings/ana, third.vrec";  // a comma: quoted in the CSV
  return {a, b, c};
}

std::vector<SessionRecord> BenSessions() {
  SessionRecord a = Record("ben", 1795500000, 1200.0);
  a.metrics.slips = 2;
  a.metrics.max_force_N = 8.0;
  a.metrics.springs_total = 86;
  SessionRecord b = Record("ben", 1795600000, 1000.0);
  b.metrics.slips = 9;
  b.metrics.max_force_N = 7.0;
  b.metrics.springs_total = 86;
  return {a, b};
}

std::unique_ptr<SessionStore> KnownStore(const std::filesystem::path& dir) {
  auto store = OpenSessionStore((dir / "sessions.sqlite").string());
  const auto ana = AnaSessions();
  const auto ben = BenSessions();
  // Out of start order on purpose: List sorts by start.
  store->Add(ana[1]);
  store->Add(ben[0]);
  store->Add(ana[2]);
  store->Add(ana[0]);
  store->Add(ben[1]);
  return store;
}

std::vector<StoredSession> FlakyStore::List(const std::string& trainee_id) {
  if (fail_list) throw RecordsError("session database test.sqlite: list sessions: disk I/O error");
  return inner_.List(trainee_id);
}

std::vector<std::string> FlakyStore::ListTrainees() {
  if (fail_list_trainees) throw RecordsError("session database test.sqlite: list trainees: disk I/O error");
  return inner_.ListTrainees();
}

}  // namespace vesica::app::testing
