#include "physics/bem/greens_function_cache.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

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

}  // namespace
}  // namespace vesica::physics
