// vesica-records: lists a station's training sessions and exports one trainee's as CSV.
//   vesica-records [--db LOCATION] list [--trainee ID]
//   vesica-records [--db LOCATION] export-csv --trainee ID [-o FILE]
// LOCATION is an SQLite file or a PostgreSQL connection string; by default $VESICA_RECORDS_DB,
// else $XDG_DATA_HOME/vesica/sessions.sqlite (see docs/records.md).

#include <CLI/CLI.hpp>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>

#include "app/records/default_location.h"
#include "app/records/session_store.h"

namespace {

using vesica::app::StoredSession;

// The units are those of the trainer and the CSV export (metric_units.h), named in the header.
void PrintSessions(const std::vector<StoredSession>& sessions) {
  std::cout << std::left << std::setw(8) << "id" << std::setw(16) << "trainee" << std::setw(22) << "started (UTC)"
            << std::setw(14) << "duration (s)" << std::setw(12) << "success" << std::setw(17) << "procedure"
            << "scenario\n";
  for (const auto& s : sessions) {
    const auto& r = s.record;
    // A replay is not the trainee's session, an unfinished one no result: neither reads as a success.
    const char* outcome = r.replay ? "replay" : r.unfinished ? "unfinished" : r.metrics.success ? "yes" : "no";
    std::cout << std::left << std::setw(8) << s.id << std::setw(16) << r.trainee_id << std::setw(22)
              << vesica::app::FormatUtcIso8601(r.started_unix_s) << std::setw(14) << std::fixed << std::setprecision(1)
              << r.metrics.duration_s << std::setw(12) << outcome << std::setw(17) << vesica::app::ProcedureKey(r.procedure)
              << r.scenario << '\n';
  }
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App cli{"Vesica session records: list sessions, export a trainee's sessions as CSV"};
  std::string location;
  cli.add_option("--db", location,
                 "SQLite file or PostgreSQL connection string (default: $VESICA_RECORDS_DB, else "
                 "$XDG_DATA_HOME/vesica/sessions.sqlite)");
  cli.require_subcommand(1);

  std::string list_trainee;
  auto* list = cli.add_subcommand("list", "list trainees, or one trainee's sessions oldest first");
  list->add_option("--trainee", list_trainee, "trainee id (default: list the trainees)");

  std::string export_trainee, output;
  auto* export_csv = cli.add_subcommand("export-csv", "one trainee's sessions as CSV (header row, one row a session)");
  export_csv->add_option("--trainee", export_trainee, "trainee id")->required();
  export_csv->add_option("-o,--output", output, "CSV file to write (default: standard output)");
  CLI11_PARSE(cli, argc, argv);

  try {
    if (location.empty()) location = vesica::app::DefaultSessionStoreLocation();
    // Opening creates a missing SQLite file; a mistyped --db should fail, not list nothing.
    if (!vesica::app::IsConnectionString(location) && !std::filesystem::exists(location)) {
      throw vesica::app::RecordsError("session database " + location + ": no such file (no session recorded there)");
    }
    // Read-only: listing never writes, so a database on a read-only disk or of another user
    // (a copy from a station, a backup) can be read, and no journal mode is switched.
    const auto store = vesica::app::OpenSessionStore(location, vesica::app::StoreAccess::kReadOnly);
    if (list->parsed()) {
      if (list_trainee.empty()) {
        for (const auto& trainee : store->ListTrainees()) std::cout << trainee << '\n';
      } else {
        PrintSessions(store->List(list_trainee));
      }
    } else if (export_csv->parsed()) {
      if (output.empty()) {
        store->ExportCsv(export_trainee, std::cout);
      } else {
        std::ofstream file(output);
        if (!file) throw vesica::app::RecordsError("cannot write " + output);
        store->ExportCsv(export_trainee, file);
        file.close();
        if (!file) throw vesica::app::RecordsError("writing " + output + " failed");
      }
    }
  } catch (const std::exception& e) {
    std::cerr << "vesica-records: " << e.what() << '\n';
    return 1;
  }
  return 0;
}
