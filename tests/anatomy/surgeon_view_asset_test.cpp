// The surgeon's-view anatomy (data/anatomy/surgeon-view, vesica-anatomy --layout surgeon-view):
// the retracted liver and its labels, the gallbladder in the fossa with the fundus over the edge,
// the ports of the American four-port technique with clear paths, and that the generator still
// reproduces the committed files.
#include <gtest/gtest.h>
#include <toml++/toml.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "anatomy_test_data.h"
#include "app/anatomy/surface_distance.h"
#include "app/anatomy/surgeon_view_layout.h"
#include "app/mesh_io/mesh_io.h"
#include "physics/mesh/mesh_topology.h"
#include "physics/mesh/mesh_validation.h"

namespace vesica::app::anatomy::testing {
namespace {

namespace fs = std::filesystem;

fs::path SurgeonViewFile(const std::string& name) { return AnatomyFile("surgeon-view/" + name); }

std::string ReadText(const fs::path& path) {
  std::ifstream file(path);
  std::stringstream text;
  text << file.rdbuf();
  return text.str();
}

Eigen::Vector3d Port(const toml::table& ports, const std::string& port, const std::string& key = "position_m") {
  const toml::array* a = ports["ports"][port][key].as_array();
  if (a == nullptr || a->size() != 3) throw std::runtime_error("ports.toml: ports." + port + "." + key + " missing");
  Eigen::Vector3d v;
  for (int k = 0; k < 3; ++k) v[k] = a->get(k)->value<double>().value();
  return v;
}

class SurgeonViewAssetTest : public ::testing::Test {
 protected:
  physics::TriangleMesh liver = ReadTriangleMesh(SurgeonViewFile("liver.vtk"), physics::SurfaceRequirement::kClosed);
  physics::TetrahedralMesh gallbladder = ReadTetrahedralMesh(SurgeonViewFile("gallbladder_1000.vtu"));
  physics::TriangleMesh gallbladder_surface =
      ReadTriangleMesh(SurgeonViewFile("gallbladder_1000_surface.vtk"), physics::SurfaceRequirement::kClosed);
  physics::TriangleMesh wall =
      ReadTriangleMesh(SurgeonViewFile("abdominal_wall.vtk"), physics::SurfaceRequirement::kAny);
  toml::table ports = toml::parse_file(SurgeonViewFile("ports.toml").string());
  RetractedLiverShape shape = SurgeonViewLiver();
  GallbladderCentreline centreline = SurgeonViewGallbladder(shape.frame);
};

TEST_F(SurgeonViewAssetTest, TheLiverIsAnAdultLiverOfAboutAThousandVertices) {
  EXPECT_NEAR(liver.num_vertices(), 1000, 50) << "the BEM's size";
  const double volume_cm3 = physics::EnclosedVolume(liver) * 1e6;
  std::printf("liver: %d vertices, %.0f cm^3\n", liver.num_vertices(), volume_cm3);
  EXPECT_GT(volume_cm3, 1000);
  EXPECT_LT(volume_cm3, 1800);
}

TEST_F(SurgeonViewAssetTest, TheBareAreaIsFixedAndTheBedIsTheFossasMedialRim) {
  const double fixed_cm2 = LabelledArea(liver, physics::kLabelFixed) * 1e4;
  int bed = 0, both = 0;
  for (int i = 0; i < liver.num_vertices(); ++i) {
    bed += (liver.vertex_labels[i] & physics::kLabelGallbladderBed) ? 1 : 0;
    both += (liver.vertex_labels[i] & physics::kLabelFixed) && (liver.vertex_labels[i] & physics::kLabelGallbladderBed);
  }
  // The physics grows its springs from the gallbladder toward the bed's centroid: medially, so
  // that the connective tissue lies in the slot beside the gallbladder, not under it.
  const Eigen::Vector3d toward_bed =
      (LabelledCentroid(liver, physics::kLabelGallbladderBed) - gallbladder.vertices.colwise().mean().transpose())
          .normalized();
  std::printf("fixed %.1f cm^2, bed %d vertices; gallbladder -> bed along the edge %.2f, out of the surface %.2f\n",
              fixed_cm2, bed, toward_bed.dot(shape.frame.Along()), toward_bed.dot(shape.frame.Out()));
  EXPECT_GT(fixed_cm2, 30);
  EXPECT_LT(fixed_cm2, 150);
  EXPECT_GE(bed, 10);
  EXPECT_EQ(both, 0);
  EXPECT_GT(toward_bed.dot(shape.frame.Along()), 0.9) << "medial, toward the left lobe";
}

TEST_F(SurgeonViewAssetTest, TheGallbladderLiesInTheFossaWithItsFundusOverTheEdge) {
  EXPECT_NEAR(gallbladder.num_vertices(), 1000, 100);
  const double volume_ml = physics::TotalVolume(gallbladder) * 1e6;
  EXPECT_GT(volume_ml, 30);
  EXPECT_LT(volume_ml, 55);
  EXPECT_NEAR(physics::EnclosedVolume(gallbladder_surface), physics::TotalVolume(gallbladder),
              1e-9 * physics::TotalVolume(gallbladder));
  double gap = 1;
  for (int i = 0; i < gallbladder_surface.num_vertices(); ++i) {
    const Eigen::Vector3d p = gallbladder_surface.vertices.row(i);
    EXPECT_FALSE(IsInsideClosedSurface(liver, p)) << "gallbladder vertex " << i << " inside the liver";
    gap = std::min(gap, DistanceToSurface(liver, p));
  }
  for (int i = 0; i < liver.num_vertices(); ++i)
    EXPECT_FALSE(IsInsideClosedSurface(gallbladder_surface, liver.vertices.row(i))) << "liver vertex " << i;
  // The fundus's far end lies past the edge's crest (across the surface, toward the diaphragm).
  double beyond_edge = 1;
  for (int i = 0; i < gallbladder_surface.num_vertices(); ++i) {
    const Eigen::Vector3d p = gallbladder_surface.vertices.row(i);
    beyond_edge = std::min(beyond_edge,
                           (p - RetractedLiverEdgePoint(shape, (p - shape.frame.edge_point_m).dot(shape.frame.Along())))
                               .dot(shape.frame.Across()));
  }
  std::printf("gallbladder %.1f ml, nearest the liver %.1f mm, fundus %.1f mm past the edge\n", volume_ml, 1e3 * gap,
              -1e3 * beyond_edge);
  EXPECT_GT(gap, 0.0015);
  EXPECT_LT(gap, 0.006);
  EXPECT_LT(beyond_edge, -0.015) << "the fundus is pushed over the edge";
}

TEST_F(SurgeonViewAssetTest, AmericanFourPortsOnTheWallWithClearPathsToTheirWork) {
  const Eigen::Vector3d grasper = Port(ports, "grasper"), hook = Port(ports, "cautery"),
                        scope = Port(ports, "laparoscope");
  for (const Eigen::Vector3d& p : {grasper, hook, scope}) EXPECT_LT(DistanceToSurface(wall, p), 0.001);
  EXPECT_NEAR(scope.x(), 0.0, 0.005) << "umbilical";
  EXPECT_LT(grasper.x(), -0.05) << "right subcostal, the left hand's grasper";
  EXPECT_NEAR(hook.x(), 0.0, 0.02) << "epigastric, the right hand's hook";
  EXPECT_GT(hook.z(), scope.z() + 0.12);
  // The hook reaches the gallbladder's side of the connective tissue's slot (all but the deepest
  // few, behind the fossa's rim: the fossa is shallow, the gallbladder's axis 2-3 mm under the
  // visceral surface; 77 of 80 reached), and the grasper Hartmann's pouch, without crossing the
  // liver.
  int slot = 0, reached = 0;
  for (int i = 0; i < gallbladder_surface.num_vertices(); ++i) {
    const Eigen::Vector3d p = gallbladder_surface.vertices.row(i);
    bool near_bed = false;
    for (int v = 0; v < liver.num_vertices() && !near_bed; ++v)
      near_bed = (liver.vertex_labels[v] & physics::kLabelGallbladderBed) &&
                 (liver.vertices.row(v).transpose() - p).norm() < 0.012;
    if (!near_bed || DistanceToSurface(liver, p) > 0.006) continue;
    ++slot;
    const auto hit = FirstRayHit(liver, hook, (p - hook).normalized());
    reached += (!hit || *hit > (p - hook).norm()) ? 1 : 0;
  }
  std::printf("the hook reaches %d of the slot's %d gallbladder vertices clear of the liver\n", reached, slot);
  EXPECT_GT(slot, 10);
  EXPECT_GE(reached, 0.9 * slot);
  const Eigen::Vector3d pouch = centreline.points_m[3];
  const auto hit = FirstRayHit(liver, grasper, (pouch - grasper).normalized());
  if (hit) {
    EXPECT_GT(*hit, (pouch - grasper).norm());
  }
  // Every organ vertex lies under the dome.
  for (const physics::TriangleMesh* organ : {&liver, &gallbladder_surface})
    for (int i = 0; i < organ->num_vertices(); ++i)
      EXPECT_TRUE(FirstRayHit(wall, organ->vertices.row(i), Eigen::Vector3d::UnitY()).has_value()) << i;
}

TEST_F(SurgeonViewAssetTest, TheVisceralSurfaceAroundTheGallbladderFacesTheUmbilicalScope) {
  const Eigen::Vector3d scope = Port(ports, "laparoscope");
  const Eigen::Vector3d middle = centreline.points_m[2];
  double facing = 0, area = 0;
  for (int f = 0; f < liver.num_triangles(); ++f) {
    const Eigen::Vector3d a = liver.vertices.row(liver.triangles(f, 0)), b = liver.vertices.row(liver.triangles(f, 1)),
                          c = liver.vertices.row(liver.triangles(f, 2));
    const Eigen::Vector3d centre = (a + b + c) / 3.0;
    if ((centre - middle).norm() > 0.06 || (centre - middle).dot(shape.frame.Out()) < -0.03) continue;
    const Eigen::Vector3d n = (b - a).cross(c - a);
    area += 0.5 * n.norm();
    if (n.normalized().dot((scope - centre).normalized()) > 0.5) facing += 0.5 * n.norm();
  }
  std::printf("visceral surface within 6 cm of the gallbladder: %.0f %% of %.0f cm^2 faces the scope within 60 deg\n",
              100 * facing / area, 1e4 * area);
  EXPECT_GT(facing / area, 0.6);
}

TEST_F(SurgeonViewAssetTest, TheInferiorEdgeIsThinAndFinelyMeshed) {
  // Along the edge's middle (5 cm either side of the fundus, clear of the round ligament's
  // notch), 8 mm in from the crest the liver is under 2 cm thick (a wedge's sharp edge, not a
  // slab's rounded end), and the mesh's edges near the crest are short (graded), so the crest is
  // not drawn as a saw.
  int samples = 0;
  for (double s = -0.05; s <= 0.05; s += 0.01) {
    const Eigen::Vector3d crest = RetractedLiverEdgePoint(shape, s);
    const Eigen::Vector3d inside = crest + 0.008 * shape.frame.Across() - 0.002 * shape.frame.Out();
    if (!IsInsideClosedSurface(liver, inside)) continue;  // the fossa (gallbladder) at this s
    const auto back = FirstRayHit(liver, inside, -shape.frame.Out());
    ASSERT_TRUE(back.has_value()) << s;
    std::printf("s = %+.0f cm: %.1f mm thick 8 mm in from the crest\n", 1e2 * s, 1e3 * (*back + 0.002));
    EXPECT_LT(*back + 0.002, 0.02) << "thickness 8 mm in from the crest at s = " << s;
    ++samples;
  }
  EXPECT_GE(samples, 5);
  double near_sum = 0, far_sum = 0;
  int near_n = 0, far_n = 0;
  for (int f = 0; f < liver.num_triangles(); ++f)
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d a = liver.vertices.row(liver.triangles(f, k));
      const Eigen::Vector3d b = liver.vertices.row(liver.triangles(f, (k + 1) % 3));
      const double d = RetractedLiverCrestDistance(shape, 0.5 * (a + b));
      if (d < 0.005) {
        near_sum += (b - a).norm();
        ++near_n;
      } else if (d > 0.04) {
        far_sum += (b - a).norm();
        ++far_n;
      }
    }
  std::printf("mesh edges: %.1f mm within 5 mm of the crest (%d), %.1f mm beyond 4 cm (%d)\n", 1e3 * near_sum / near_n,
              near_n, 1e3 * far_sum / far_n, far_n);
  EXPECT_LT(near_sum / near_n, 0.005);
  EXPECT_LT(near_sum / near_n, 0.5 * far_sum / far_n);
}

TEST(SurgeonViewReproducibilityTest, GeneratorReproducesTheCommittedFiles) {
  const auto dir = fs::temp_directory_path() /
                   ("vesica_surgeon_view_test_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()));
  fs::remove_all(dir);
  WriteAnatomy(GenerateAnatomy(SurgeonViewAnatomyOptions()), dir);
  const physics::TriangleMesh liver = ReadTriangleMesh(dir / "liver.vtk", physics::SurfaceRequirement::kClosed);
  const physics::TriangleMesh committed =
      ReadTriangleMesh(SurgeonViewFile("liver.vtk"), physics::SurfaceRequirement::kClosed);
  EXPECT_EQ(liver.num_vertices(), committed.num_vertices());
  EXPECT_EQ(liver.num_triangles(), committed.num_triangles());
  EXPECT_NEAR(physics::EnclosedVolume(liver), physics::EnclosedVolume(committed), 1e-12);
  EXPECT_EQ(liver.vertex_labels, committed.vertex_labels);
  const physics::TetrahedralMesh gb = ReadTetrahedralMesh(dir / "gallbladder_1000.vtu");
  const physics::TetrahedralMesh committed_gb = ReadTetrahedralMesh(SurgeonViewFile("gallbladder_1000.vtu"));
  EXPECT_EQ(gb.num_vertices(), committed_gb.num_vertices());
  EXPECT_EQ(gb.num_tets(), committed_gb.num_tets());
  EXPECT_NEAR(physics::TotalVolume(gb), physics::TotalVolume(committed_gb), 1e-12);
  EXPECT_EQ(ReadText(dir / "ports.toml"), ReadText(SurgeonViewFile("ports.toml")));
  for (const char* name : {"liver.vtk", "gallbladder_1000.vtu", "gallbladder_1000_surface.vtk", "abdominal_wall.vtk"})
    EXPECT_EQ(ReadText(dir / name), ReadText(SurgeonViewFile(name))) << name << " byte for byte";
  fs::remove_all(dir);
}

}  // namespace
}  // namespace vesica::app::anatomy::testing
