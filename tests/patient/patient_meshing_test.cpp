// Meshing (seed 3.3): each surface lies within one voxel of its label boundary, is closed, and a
// NIfTI round trip gives the same meshes.
#include "app/patient/patient_meshing.h"

#include <gtest/gtest.h>

#include <Eigen/LU>
#include <algorithm>
#include <filesystem>

#include "app/patient/patient_files.h"
#include "app/patient/synthetic_patient.h"
#include "physics/patient/breathing_patient.h"
#include "physics/patient/patient_labels.h"

namespace vesica::app::patient {
namespace {
namespace label = physics::patient_label;

const PatientVolume& Synthetic() {
  static const PatientVolume volume = GenerateSyntheticPatient();
  return volume;
}

// The largest distance from a vertex to the label boundary (the faces between a voxel inside and
// one outside), searched over the faces within 3 voxels.
double WorstDistanceToBoundary(const physics::LabelVolume& v, const std::vector<std::uint8_t>& labels,
                               const physics::TriangleMesh& mesh) {
  std::array<bool, 256> in{};
  for (std::uint8_t l : labels) in[l] = true;
  const auto inside = [&](int i, int j, int k) {
    if (i < 0 || j < 0 || k < 0 || i >= v.dims[0] || j >= v.dims[1] || k >= v.dims[2]) return false;
    return in[v.At(i, j, k)];
  };
  const Eigen::Matrix3d to_index = (v.direction * v.spacing_m.asDiagonal()).inverse();
  double worst = 0.0;
  for (int p = 0; p < mesh.num_vertices(); ++p) {
    const Eigen::Vector3d x = mesh.vertices.row(p).transpose();
    const Eigen::Vector3d ijk = to_index * (x - v.origin_m);
    double best = INFINITY;
    for (int k = int(std::floor(ijk.z())) - 3; k <= int(std::floor(ijk.z())) + 3; ++k)
      for (int j = int(std::floor(ijk.y())) - 3; j <= int(std::floor(ijk.y())) + 3; ++j)
        for (int i = int(std::floor(ijk.x())) - 3; i <= int(std::floor(ijk.x())) + 3; ++i) {
          if (!inside(i, j, k)) continue;
          const int step[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
          for (const auto& s : step)
            if (!inside(i + s[0], j + s[1], k + s[2])) {
              const Eigen::Vector3d face =
                  v.origin_m + v.direction * Eigen::Vector3d((i + 0.5 * s[0]) * v.spacing_m.x(),
                                                             (j + 0.5 * s[1]) * v.spacing_m.y(),
                                                             (k + 0.5 * s[2]) * v.spacing_m.z());
              best = std::min(best, (face - x).norm());
            }
        }
    worst = std::max(worst, best);
  }
  return worst;
}

TEST(PatientMeshingTest, SurfacesLieWithinOneVoxelOfTheLabelBoundary) {
  const physics::LabelVolume& v = Synthetic().labels;
  const double voxel = v.spacing_m.maxCoeff();
  for (const auto& [organ, labels] : std::vector<std::pair<std::string, std::vector<std::uint8_t>>>{
           {"liver", {label::kLiver, label::kLiverCapsule, label::kTumour}},
           {"diaphragm", {label::kDiaphragmMuscle, label::kDiaphragmTendon}},
           {"tumour", {label::kTumour}},
           {"rib_r8", {label::Rib(false, 8), label::Cartilage(false, 8)}}}) {
    const physics::TriangleMesh mesh = MeshLabels(v, labels, organ);
    ASSERT_GT(mesh.num_triangles(), 50) << organ;
    const double worst = WorstDistanceToBoundary(v, labels, mesh);
    EXPECT_LE(worst, voxel) << organ;
    std::printf("%s: %d vertices, %d triangles, farthest vertex %.2f mm from the label boundary\n", organ.c_str(),
                mesh.num_vertices(), mesh.num_triangles(), 1e3 * worst);
  }
}

TEST(PatientMeshingTest, SurfacesAreClosedAndOutward) {
  const physics::LabelVolume& v = Synthetic().labels;
  const physics::TriangleMesh liver = MeshLabels(v, {label::kLiver, label::kLiverCapsule, label::kTumour}, "liver");
  long voxels = 0;
  for (std::uint8_t l : v.labels) voxels += label::IsLiver(l);
  EXPECT_NEAR(physics::EnclosedVolume(liver), voxels * v.VoxelVolume_m3(), 0.05 * voxels * v.VoxelVolume_m3());
  const physics::TriangleMesh tumour = MeshLabels(v, {label::kTumour}, "tumour");
  EXPECT_NEAR(physics::EnclosedVolume(tumour), 4.0 / 3.0 * M_PI * std::pow(0.0075, 3),
              0.25 * 4.0 / 3.0 * M_PI * std::pow(0.0075, 3));
}

TEST(PatientMeshingTest, NiftiRoundTripGivesTheSameMeshes) {
  const auto dir = std::filesystem::temp_directory_path() / ("vesica-patient-mesh-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  WriteNiftiPatient(Synthetic(), dir / "ct.nii.gz", dir / "labels.nii.gz");
  const physics::LabelVolume read = ReadNiftiLabels(dir / "labels.nii.gz");
  const std::vector<std::uint8_t> liver = {label::kLiver, label::kLiverCapsule, label::kTumour};
  const physics::TriangleMesh a = MeshLabels(Synthetic().labels, liver, "liver");
  const physics::TriangleMesh b = MeshLabels(read, liver, "liver");
  ASSERT_EQ(a.num_vertices(), b.num_vertices());
  ASSERT_EQ(a.triangles, b.triangles);
  EXPECT_LT((a.vertices - b.vertices).cwiseAbs().maxCoeff(), 1e-9);
  std::filesystem::remove_all(dir);
}

TEST(PatientMeshingTest, WholePatientHasEveryOrgan) {
  const std::vector<OrganSurface> organs = MeshPatient(Synthetic().labels);
  EXPECT_EQ(organs.size(), 9u + 24u);
  for (const OrganSurface& o : organs) EXPECT_GT(o.mesh.num_triangles(), 20) << o.organ;
  EXPECT_THROW((void)MeshLabels(Synthetic().labels, {250}, "nothing"), std::invalid_argument);
}

// The liver's rendered surface moves with its ChainMail lattice: still at end tidal, its top follows
// the tendon at peak inspiration and its lowest point moves less.
TEST(PatientMeshingTest, LiverSurfaceMovesWithItsLattice) {
  const physics::LabelVolume& v = Synthetic().labels;
  const physics::TriangleMesh liver = MeshLabels(v, {label::kLiver, label::kLiverCapsule, label::kTumour}, "liver");
  const auto model = physics::BuildBreathingPatientModel(v);
  std::vector<Eigen::Vector3d> vertices;
  for (int p = 0; p < liver.num_vertices(); ++p) vertices.push_back(liver.vertices.row(p).transpose());
  const physics::LatticeEmbedding embedding = physics::EmbedPoints(model->liver.lattice, v, vertices);
  for (std::size_t p = 0; p < vertices.size(); ++p) ASSERT_GT(embedding.first[p + 1], embedding.first[p]) << p;
  physics::BreathingPatient patient(model);
  patient.Update(0.0);
  for (std::size_t p = 0; p < vertices.size(); ++p)
    ASSERT_EQ(embedding.Displacement(p, patient.liver_displacement()), Eigen::Vector3d::Zero());
  patient.Update(1.0);  // peak inspiration at 0.25 Hz
  const double tendon = patient.snapshot().tendon_displacement_m;
  std::size_t top = 0, bottom = 0;
  for (std::size_t p = 0; p < vertices.size(); ++p) {
    if (vertices[p].z() > vertices[top].z()) top = p;
    if (vertices[p].z() < vertices[bottom].z()) bottom = p;
  }
  const double top_dz = embedding.Displacement(top, patient.liver_displacement()).z();
  const double bottom_dz = embedding.Displacement(bottom, patient.liver_displacement()).z();
  EXPECT_NEAR(top_dz, -tendon, 0.2 * tendon);
  EXPECT_LT(std::abs(bottom_dz), std::abs(top_dz));
}

}  // namespace
}  // namespace vesica::app::patient
