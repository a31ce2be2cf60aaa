#include "tests/records/postgres_test_server.h"

#include <fcntl.h>
#include <libpq-fe.h>
#include <pwd.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace vesica::app::testing {
namespace {

constexpr const char* kPort = "5432";  // names the socket file; nothing listens on TCP

// The newest /usr/lib/postgresql/<major>/bin that has initdb; "" when none.
std::string FindPostgresBinDir() {
  std::string best;
  int best_major = -1;
  std::error_code error;
  for (const auto& entry : std::filesystem::directory_iterator("/usr/lib/postgresql", error)) {
    const auto bin = entry.path() / "bin";
    if (!std::filesystem::exists(bin / "initdb")) continue;
    const int major = std::atoi(entry.path().filename().c_str());
    if (major > best_major) best_major = major, best = bin.string();
  }
  return best;
}

std::string Tail(const std::string& path, std::size_t max_chars = 2000) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  const std::string all = text.str();
  return all.size() > max_chars ? "..." + all.substr(all.size() - max_chars) : all;
}

}  // namespace

PostgresTestServer::PostgresTestServer() {
  bin_dir_ = FindPostgresBinDir();
  if (bin_dir_.empty()) {
    error_ =
        "no PostgreSQL server binaries (/usr/lib/postgresql/*/bin/initdb): install the `postgresql` package "
        "(scripts/deps.txt)";
    return;
  }
  dir_ = std::make_unique<TempDir>("vesica-pg");
  const std::string dir = dir_->path().string();
  if (geteuid() == 0) {
    const passwd* postgres = getpwnam("postgres");
    if (postgres == nullptr) {
      error_ =
          "running as root and there is no `postgres` user to run the server as (the postgresql package creates it)";
      return;
    }
    if (chown(dir.c_str(), postgres->pw_uid, postgres->pw_gid) != 0) {
      error_ = "chown " + dir + " to postgres failed: " + std::strerror(errno);
      return;
    }
  }
  std::string why;
  const std::string data = dir + "/data";
  const std::string cached = TemplatePath();
  const bool from_template = UsableTemplate(cached);
  if (from_template) {
    if (!RunAsPostgres({"/bin/cp", "-a", cached, data}, dir + "/cp.log", why)) {
      error_ = "copying the cached cluster " + cached + " failed (" + why + "):\n" + Tail(dir + "/cp.log");
      return;
    }
  } else {
    if (!RunAsPostgres(
            {bin_dir_ + "/initdb", "-D", data, "-A", "trust", "-U", "postgres", "-N", "-E", "UTF8", "--locale=C"},
            dir + "/initdb.log", why)) {
      error_ = "initdb failed (" + why + "):\n" + Tail(dir + "/initdb.log");
      return;
    }
    // initdb takes seconds and CTest runs every test in a process of its own: keep a copy for
    // the next ones. rename() publishes it whole or not at all; losing a race to another
    // process is fine (its copy is as good).
    const std::string staging = dir + "/template";
    if (RunAsPostgres({"/bin/cp", "-a", data, staging}, dir + "/cp.log", why)) {
      std::rename(staging.c_str(), cached.c_str());
    }
  }
  // -F: no fsync (the tests kill clients, not the server); socket only, in our folder.
  const std::string server_options =
      "-F -c listen_addresses='' -k " + dir + " -p " + kPort + " -c max_connections=30 -c shared_buffers=16MB";
  if (!RunAsPostgres({bin_dir_ + "/pg_ctl", "-D", dir + "/data", "-l", dir + "/server.log", "-w", "-t", "60", "-o",
                      server_options, "start"},
                     dir + "/pg_ctl.log", why)) {
    error_ = "pg_ctl start failed (" + why + "):\n" + Tail(dir + "/pg_ctl.log") + "\nserver log:\n" +
             Tail(dir + "/server.log") +
             (from_template ? "\n(the cluster was a copy of " + cached + "; remove that folder if it is broken)" : "");
    return;
  }
  running_ = true;
}

PostgresTestServer::~PostgresTestServer() { Stop(); }

uid_t PostgresTestServer::ServerUid() {
  if (geteuid() != 0) return geteuid();
  const passwd* postgres = getpwnam("postgres");
  return postgres != nullptr ? postgres->pw_uid : 0;
}

std::string PostgresTestServer::TemplatePath() const {
  const std::string major = std::filesystem::path(bin_dir_).parent_path().filename().string();
  return "/tmp/vesica-pg-template-" + std::to_string(ServerUid()) + "-" + major;
}

bool PostgresTestServer::UsableTemplate(const std::string& path) {
  // /tmp is shared: only a folder the server's user owns and nobody else can write is trusted.
  struct stat info {};
  if (lstat(path.c_str(), &info) != 0 || !S_ISDIR(info.st_mode)) return false;
  if (info.st_uid != ServerUid() || (info.st_mode & 077) != 0) return false;
  for (const char* file : {"PG_VERSION", "postgresql.conf", "global/pg_control"}) {
    if (!std::filesystem::exists(std::filesystem::path(path) / file)) return false;
  }
  return true;
}

PostgresTestServer& PostgresTestServer::Shared() {
  static PostgresTestServer server;
  return server;
}

void PostgresTestServer::Stop() {
  if (!running_) return;
  running_ = false;
  std::string why;
  const std::string dir = dir_->path().string();
  RunAsPostgres({bin_dir_ + "/pg_ctl", "-D", dir + "/data", "-m", "immediate", "-w", "stop"}, dir + "/stop.log", why);
}

bool PostgresTestServer::RunAsPostgres(const std::vector<std::string>& argv, const std::string& log_path,
                                       std::string& why) {
  std::vector<std::string> full;
  if (geteuid() == 0) full = {"/usr/sbin/runuser", "-u", "postgres", "--"};
  full.insert(full.end(), argv.begin(), argv.end());
  std::vector<char*> args;
  for (auto& a : full) args.push_back(a.data());
  args.push_back(nullptr);

  const int log = open(log_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
  if (log < 0) {
    why = "cannot create " + log_path + ": " + std::strerror(errno);
    return false;
  }
  const pid_t pid = fork();
  if (pid == 0) {
    // The server inherits these: the log file, never the test's own stdout/stderr pipes.
    dup2(log, STDOUT_FILENO);
    dup2(log, STDERR_FILENO);
    const int null = open("/dev/null", O_RDONLY);
    dup2(null, STDIN_FILENO);
    execv(args[0], args.data());
    _exit(127);
  }
  close(log);
  if (pid < 0) {
    why = std::string("fork: ") + std::strerror(errno);
    return false;
  }
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (WIFEXITED(status) && WEXITSTATUS(status) == 0) return true;
  why = full[geteuid() == 0 ? 4 : 0] +
        (WIFEXITED(status) ? " exited with " + std::to_string(WEXITSTATUS(status)) : std::string(" was killed"));
  return false;
}

std::string PostgresTestServer::ConnectionString(const std::string& dbname) const {
  return "host=" + (dir_ ? dir_->path().string() : std::string("/nonexistent")) + " port=" + kPort +
         " user=postgres dbname=" + dbname;
}

std::string PostgresTestServer::AdminQuery(const std::string& dbname, const std::string& sql) const {
  return Query(ConnectionString(dbname), sql);
}

std::string PostgresTestServer::Query(const std::string& conninfo, const std::string& sql) {
  PGconn* conn = PQconnectdb(conninfo.c_str());
  std::string value, failure;
  if (PQstatus(conn) != CONNECTION_OK) {
    failure = PQerrorMessage(conn);
  } else {
    PQsetNoticeProcessor(
        conn, [](void*, const char*) {}, nullptr);
    PGresult* result = PQexec(conn, sql.c_str());
    const auto status = PQresultStatus(result);
    if (status != PGRES_COMMAND_OK && status != PGRES_TUPLES_OK)
      failure = PQresultErrorMessage(result);
    else if (PQntuples(result) > 0 && PQnfields(result) > 0)
      value = PQgetvalue(result, 0, 0);
    PQclear(result);
  }
  PQfinish(conn);
  if (!failure.empty()) throw std::runtime_error("test server: " + sql + ": " + failure);
  return value;
}

std::string PostgresTestServer::NewDatabase() {
  if (!running_) throw std::runtime_error("test PostgreSQL server is not running: " + error_);
  const std::string name = "vesica_test_" + std::to_string(getpid()) + "_" + std::to_string(++next_database_);
  AdminQuery("postgres", "CREATE DATABASE " + name);
  return ConnectionString(name);
}

}  // namespace vesica::app::testing
