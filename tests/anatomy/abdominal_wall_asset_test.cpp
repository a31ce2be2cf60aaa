// The committed abdominal wall and ports.toml: ports on the wall, a dome over the organs, and a
// laparoscope aimed at the gallbladder.
#include <gtest/gtest.h>
#include <toml++/toml.h>

#include "anatomy_test_data.h"
#include "app/anatomy/surface_distance.h"

namespace vesica::app::anatomy::testing {
namespace {

Eigen::Vector3d ReadVector(const toml::table& ports, const std::string& port, const std::string& key) {
  const toml::array* a = ports["ports"][port][key].as_array();
  if (a == nullptr || a->size() != 3) throw std::runtime_error("ports.toml: ports." + port + "." + key + " missing");
  Eigen::Vector3d v;
  for (int k = 0; k < 3; ++k) v[k] = a->get(k)->value<double>().value();
  return v;
}

class AbdominalWallAssetTest : public ::testing::Test {
 protected:
  physics::TriangleMesh wall = LoadAbdominalWall();
  toml::table ports = toml::parse_file(AnatomyFile("ports.toml").string());
};

TEST_F(AbdominalWallAssetTest, TrocarsAndLaparoscopePortLieOnTheWall) {
  for (const char* port : {"grasper", "cautery", "laparoscope"}) {
    EXPECT_LT(DistanceToSurface(wall, ReadVector(ports, port, "position_m")), 0.001) << port;
  }
}

TEST_F(AbdominalWallAssetTest, FourPortLayoutAroundTheGallbladder) {
  const Eigen::Vector3d grasper = ReadVector(ports, "grasper", "position_m");
  const Eigen::Vector3d cautery = ReadVector(ports, "cautery", "position_m");
  const Eigen::Vector3d scope = ReadVector(ports, "laparoscope", "position_m");
  const physics::TriangleMesh gallbladder = LoadGallbladderSurface(3000);
  const Eigen::Vector3d target = gallbladder.vertices.colwise().mean();
  EXPECT_NEAR(scope.x(), 0.0, 0.01) << "umbilicus is on the midline";
  EXPECT_LT(scope.z(), target.z() - 0.08) << "umbilicus is well caudal of the gallbladder";
  EXPECT_LT(grasper.x(), cautery.x()) << "grasper port is lateral (patient's right) of the hook's";
  EXPECT_GT(cautery.z(), scope.z() + 0.08) << "hook port is well cranial of the umbilicus";
  for (const Eigen::Vector3d& p : {grasper, cautery, scope}) {
    const double reach = (p - target).norm();  // 30-36 cm instruments need this inside them
    EXPECT_GT(reach, 0.06);
    EXPECT_LT(reach, 0.25);
  }
  EXPECT_LT((ReadVector(ports, "laparoscope", "look_at_m") - target).norm(), 0.02);
}

TEST_F(AbdominalWallAssetTest, HookAndLaparoscopeReachTheLiverBedWithoutCrossingTheLiver) {
  // The liver is not retracted in the scene and shafts do not collide with it: a straight path
  // from the port to the membrane must not pass through the liver, or the hook would burn
  // behind 5 cm of liver (as it did from the old epigastric port at (-0.01, 0.10)).
  const physics::TriangleMesh liver = LoadLiver();
  const physics::TriangleMesh gallbladder = LoadGallbladderSurface(1000);
  int bed_points = 0;
  for (const char* port : {"cautery", "laparoscope"}) {
    const Eigen::Vector3d from = ReadVector(ports, port, "position_m");
    for (int i = 0; i < gallbladder.num_vertices(); ++i) {
      const Eigen::Vector3d bed = gallbladder.vertices.row(i).transpose();
      if (DistanceToSurface(liver, bed) > 0.008) continue;  // where the connective tissue is
      ++bed_points;
      const double distance = (bed - from).norm();
      const auto hit = FirstRayHit(liver, from, (bed - from) / distance);
      if (hit.has_value()) EXPECT_GT(*hit, distance) << port << " -> gallbladder vertex " << i;
    }
  }
  EXPECT_GT(bed_points, 100);
  // The grasper reaches the gallbladder's middle (its fundus side) clear of the liver.
  const Eigen::Vector3d grasper = ReadVector(ports, "grasper", "position_m");
  const Eigen::Vector3d target = ReadVector(ports, "laparoscope", "look_at_m");
  const auto hit = FirstRayHit(liver, grasper, (target - grasper).normalized());
  if (hit.has_value()) EXPECT_GT(*hit, (target - grasper).norm());
}

TEST_F(AbdominalWallAssetTest, DomeCoversTheOrgans) {
  // From every organ vertex, straight up (anterior) meets the wall: nothing pokes through it.
  for (const physics::TriangleMesh& organ : {LoadLiver(), LoadGallbladderSurface(1000)}) {
    for (int i = 0; i < organ.num_vertices(); ++i) {
      const auto hit = FirstRayHit(wall, organ.vertices.row(i), Eigen::Vector3d::UnitY());
      ASSERT_TRUE(hit.has_value()) << "organ vertex " << i << " is not under the dome";
      EXPECT_GT(*hit, 0.01) << "organ vertex " << i << " touches the wall";
    }
  }
}

}  // namespace
}  // namespace vesica::app::anatomy::testing
