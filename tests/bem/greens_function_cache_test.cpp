#include "physics/bem/greens_function_cache.h"

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include "bem_test_support.h"
#include "physics/bem/bem_model.h"

namespace vesica::physics {
namespace {

std::string TempPath(const std::string& name) {
  return (std::filesystem::temp_directory_path() / ("vesica_bem_" + std::to_string(::getpid()) + "_" + name)).string();
}

TEST(GreensFunctionCacheTest, RoundTripIsBitExactAndKeyMismatchIsStale) {
  const std::string path = TempPath("roundtrip.bin");
  const Eigen::MatrixXd greens = Eigen::MatrixXd::Random(30, 21);
  WriteGreensCache(path, 42, greens);
  GreensCacheStatus status{};
  const auto loaded = ReadGreensCache(path, 42, status);
  ASSERT_TRUE(loaded.has_value());
  EXPECT_EQ(status, GreensCacheStatus::kLoaded);
  EXPECT_EQ(*loaded, greens);
  EXPECT_FALSE(ReadGreensCache(path, 43, status).has_value());
  EXPECT_EQ(status, GreensCacheStatus::kStale);
  EXPECT_FALSE(ReadGreensCache(path + ".absent", 42, status).has_value());
  EXPECT_EQ(status, GreensCacheStatus::kMissing);
  std::filesystem::remove(path);
}

TEST(GreensFunctionCacheTest, FlippedByteOrTruncationIsCorrupt) {
  const std::string path = TempPath("corrupt.bin");
  WriteGreensCache(path, 7, Eigen::MatrixXd::Random(12, 9));
  {
    std::fstream f(path, std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(100);
    char byte = 0;
    f.read(&byte, 1);
    byte = static_cast<char>(byte ^ 0x10);
    f.seekp(100);
    f.write(&byte, 1);
  }
  GreensCacheStatus status{};
  EXPECT_FALSE(ReadGreensCache(path, 7, status).has_value());
  EXPECT_EQ(status, GreensCacheStatus::kCorrupt);
  WriteGreensCache(path, 7, Eigen::MatrixXd::Random(12, 9));
  std::filesystem::resize_file(path, std::filesystem::file_size(path) - 9);
  EXPECT_FALSE(ReadGreensCache(path, 7, status).has_value());
  EXPECT_EQ(status, GreensCacheStatus::kCorrupt);
  std::filesystem::remove(path);
}

// The model precompute writes the cache, trusts it next time, and rebuilds (same result) when
// the file is corrupted or the material or the fixed region changed.
TEST(GreensFunctionCacheTest, PrecomputeUsesValidCacheAndRebuildsCorruptOrStaleOne) {
  const std::string path = TempPath("model.bin");
  std::filesystem::remove(path);
  const TriangleMesh mesh = testing::LiverLikeEllipsoid(60);
  BemPrecomputeOptions options;
  options.cache_path = path;
  GreensCacheStatus status{};
  const BemModel first = PrecomputeBemModel(mesh, LiverMaterial(), "cache test", options, &status);
  EXPECT_EQ(status, GreensCacheStatus::kMissing);
  const BemModel second = PrecomputeBemModel(mesh, LiverMaterial(), "cache test", options, &status);
  EXPECT_EQ(status, GreensCacheStatus::kLoaded);
  EXPECT_EQ(second.greens, first.greens);

  { std::ofstream(path, std::ios::binary | std::ios::in | std::ios::out).seekp(64).put('\x7f'); }
  const BemModel rebuilt = PrecomputeBemModel(mesh, LiverMaterial(), "cache test", options, &status);
  EXPECT_EQ(status, GreensCacheStatus::kCorrupt);
  EXPECT_EQ(rebuilt.greens, first.greens);

  const BemModel softer = PrecomputeBemModel(mesh, ElasticMaterial{85e3, 0.4, 1060.0}, "cache test", options, &status);
  EXPECT_EQ(status, GreensCacheStatus::kStale);
  // Same Poisson ratio, half the modulus: free-node displacements per unit traction double.
  EXPECT_NEAR((softer.greens.row(3 * first.layout.free_nodes[0]) - 2.0 * first.greens.row(3 * first.layout.free_nodes[0])).norm(),
              0.0, 1e-9 * first.greens.row(3 * first.layout.free_nodes[0]).norm());

  TriangleMesh refixed = mesh;
  refixed.vertex_labels(first.layout.free_nodes[0]) = kLabelFixed;
  PrecomputeBemModel(refixed, LiverMaterial(), "cache test", options, &status);
  EXPECT_EQ(status, GreensCacheStatus::kStale);
  std::filesystem::remove(path);
}

// The cache's failure cases: the precompute still returns the same model, reports the cache
// problem once through on_warning, and leaves no temporary file behind.
class GreensCacheFailureTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = TempPath("failure_dir");
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
    if (reference_ == nullptr) reference_ = new BemModel(PrecomputeBemModel(Mesh(), LiverMaterial(), "cache test"));
  }
  void TearDown() override {
    std::error_code ignored;
    std::filesystem::permissions(dir_, std::filesystem::perms::all, ignored);
    std::filesystem::remove_all(dir_);
  }
  static TriangleMesh Mesh() { return testing::LiverLikeEllipsoid(60); }
  // Precomputes with the cache at `path`; the warnings it gave land in warnings_.
  BemModel Precompute(const std::string& path, GreensCacheStatus* status = nullptr) {
    BemPrecomputeOptions options;
    options.cache_path = path;
    options.on_warning = [this](const std::string& w) { warnings_.push_back(w); };
    return PrecomputeBemModel(Mesh(), LiverMaterial(), "cache test", options, status);
  }
  // Files in dir_ whose name contains ".tmp".
  std::vector<std::string> Temporaries() const {
    std::vector<std::string> found;
    for (const auto& entry : std::filesystem::recursive_directory_iterator(dir_))
      if (entry.path().filename().string().find(".tmp") != std::string::npos &&
          entry.path().filename() != "leftover.greens.tmp")
        found.push_back(entry.path().string());
    return found;
  }
  // Runs `body` in a forked child; returns its exit code (99: it threw; -1: a signal ended it).
  static int InChild(const std::function<int()>& body) {
    const pid_t pid = fork();
    if (pid == 0) {
      int code = 99;
      try {
        code = body();
      } catch (...) {
      }
      _exit(code);  // never back into the parent's test run
    }
    int status = 0;
    waitpid(pid, &status, 0);
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }
  std::filesystem::path dir_;
  std::vector<std::string> warnings_;
  static BemModel* reference_;
};
BemModel* GreensCacheFailureTest::reference_ = nullptr;

TEST_F(GreensCacheFailureTest, CachePathThatIsADirectoryRunsUncachedAndSaysSoOnce) {
  const auto path = dir_ / "liver.greens";
  std::filesystem::create_directories(path);
  GreensCacheStatus status{};
  const BemModel model = Precompute(path.string(), &status);
  EXPECT_EQ(status, GreensCacheStatus::kUnreadable);
  EXPECT_EQ(model.greens, reference_->greens);
  ASSERT_EQ(warnings_.size(), 1u);
  EXPECT_NE(warnings_[0].find(path.string()), std::string::npos) << warnings_[0];
  EXPECT_NE(warnings_[0].find("without the cache"), std::string::npos) << warnings_[0];
  EXPECT_TRUE(Temporaries().empty());
}

TEST_F(GreensCacheFailureTest, CacheFolderThatIsAFileRunsUncached) {
  std::ofstream(dir_ / "not-a-folder") << "x";
  const auto path = dir_ / "not-a-folder" / "liver.greens";
  GreensCacheStatus status{};
  const BemModel model = Precompute(path.string(), &status);
  EXPECT_EQ(status, GreensCacheStatus::kUnreadable);
  EXPECT_EQ(model.greens, reference_->greens);
  ASSERT_EQ(warnings_.size(), 1u);
  EXPECT_NE(warnings_[0].find("Not a directory"), std::string::npos) << warnings_[0];
}

TEST_F(GreensCacheFailureTest, LeftoverTemporaryOfAnEarlierRunIsNoObstacle) {
  // The old writer's fixed temporary name, left as a directory by a crashed or odd run.
  const auto path = dir_ / "leftover.greens";
  std::filesystem::create_directories(path.string() + ".tmp");
  GreensCacheStatus status{};
  Precompute(path.string(), &status);
  EXPECT_EQ(status, GreensCacheStatus::kMissing);
  EXPECT_TRUE(warnings_.empty()) << warnings_.front();
  Precompute(path.string(), &status);
  EXPECT_EQ(status, GreensCacheStatus::kLoaded);
}

TEST_F(GreensCacheFailureTest, ReadOnlyCacheFolderRunsUncached) {
  // As root the permission bits do not stop writes: the child drops to "nobody" first.
  std::filesystem::permissions(dir_, std::filesystem::perms::owner_all | std::filesystem::perms::group_read |
                                         std::filesystem::perms::group_exec | std::filesystem::perms::others_read |
                                         std::filesystem::perms::others_exec);
  const auto path = dir_ / "liver.greens";
  const int code = InChild([&] {
    if (getuid() == 0 && (setgid(65534) != 0 || setuid(65534) != 0)) return 10;
    GreensCacheStatus status{};
    const BemModel model = Precompute(path.string(), &status);
    if (status != GreensCacheStatus::kMissing) return 11;
    if (!(model.greens == reference_->greens)) return 12;
    if (warnings_.size() != 1 || warnings_[0].find("Permission denied") == std::string::npos) return 13;
    return 0;
  });
  EXPECT_EQ(code, 0) << "10: setuid, 11: status, 12: model, 13: not one 'Permission denied' warning, 99: threw";
  EXPECT_FALSE(std::filesystem::exists(path));
  EXPECT_TRUE(Temporaries().empty());
}

TEST_F(GreensCacheFailureTest, FullDiskRemovesThePartialTemporaryFile) {
  // A file size limit makes write() fail with EFBIG partway, as a full disk fails with ENOSPC.
  const auto path = dir_ / "liver.greens";
  const int code = InChild([&] {
    signal(SIGXFSZ, SIG_IGN);
    const rlimit limit{4096, 4096};
    if (setrlimit(RLIMIT_FSIZE, &limit) != 0) return 10;
    GreensCacheStatus status{};
    const BemModel model = Precompute(path.string(), &status);
    if (!(model.greens == reference_->greens)) return 12;
    if (warnings_.size() != 1 || warnings_[0].find("cannot write") == std::string::npos) return 13;
    return 0;
  });
  EXPECT_EQ(code, 0) << "10: setrlimit, 12: model, 13: not one 'cannot write' warning, 99: threw";
  EXPECT_FALSE(std::filesystem::exists(path));
  EXPECT_TRUE(Temporaries().empty()) << Temporaries().front();
}

TEST_F(GreensCacheFailureTest, TwoProcessesFillingTheSameCacheBothSucceed) {
  const auto path = (dir_ / "shared.greens").string();
  const Eigen::MatrixXd greens = Eigen::MatrixXd::Random(300, 270);
  std::vector<pid_t> children;
  for (int c = 0; c < 2; ++c) {
    const pid_t pid = fork();
    if (pid == 0) {
      try {
        for (int i = 0; i < 100; ++i) WriteGreensCache(path, 5, greens);
      } catch (...) {
        _exit(1);
      }
      _exit(0);
    }
    children.push_back(pid);
  }
  for (const pid_t pid : children) {
    int status = 0;
    waitpid(pid, &status, 0);
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << "a writer failed";
  }
  GreensCacheStatus status{};
  const auto loaded = ReadGreensCache(path, 5, status);
  EXPECT_EQ(status, GreensCacheStatus::kLoaded);
  ASSERT_TRUE(loaded.has_value());
  EXPECT_EQ(*loaded, greens);
  EXPECT_TRUE(Temporaries().empty());
}

}  // namespace
}  // namespace vesica::physics
