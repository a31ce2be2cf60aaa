// Section 4's validation step: warping a CT by the registration's displacement field and taking a
// slice (physics/registration/slice_warp.h), against the analytically warped slice.

#include "physics/registration/slice_warp.h"

#include <gtest/gtest.h>

#include <Eigen/LU>

#include "physics/mesh/primitives.h"

namespace vesica::physics {
namespace {

// A 40^3 grid of 2 mm voxels with a bright ball (1000 HU in 0 HU) of radius 15 mm.
struct BallVolume {
  LabelVolume grid;
  std::vector<std::int16_t> ct;
  Eigen::Vector3d centre_m{0.040, 0.040, 0.040};
  double radius_m = 0.015;
  bool Inside(const Eigen::Vector3d& p) const { return (p - centre_m).norm() < radius_m; }
};

BallVolume MakeBall() {
  BallVolume v;
  v.grid.dims = {40, 40, 40};
  v.grid.spacing_m = Eigen::Vector3d::Constant(0.002);
  v.ct.resize(40 * 40 * 40);
  for (int k = 0; k < 40; ++k)
    for (int j = 0; j < 40; ++j)
      for (int i = 0; i < 40; ++i) v.ct[v.grid.Index(i, j, k)] = v.Inside(v.grid.Position(i, j, k)) ? 1000 : 0;
  return v;
}

// x = X + u(X) with u affine: exact on linear tets, invertible analytically.
const Eigen::Matrix3d kGradient =
    (Eigen::Matrix3d() << 0.10, 0.05, 0.0, -0.03, 0.08, 0.02, 0.0, 0.06, -0.05).finished();
const Eigen::Vector3d kTranslation(0.0047, -0.0033, 0.0021);
const Eigen::Vector3d kPivot(0.040, 0.040, 0.040);
Eigen::Vector3d Forward(const Eigen::Vector3d& X) { return X + kGradient * (X - kPivot) + kTranslation; }
Eigen::Vector3d Inverse(const Eigen::Vector3d& x) {
  return kPivot + (Eigen::Matrix3d::Identity() + kGradient).inverse() * (x - kPivot - kTranslation);
}

// Fraction of the pixels whose class (ball or not) differs from the analytic slice's at every
// pixel within one voxel of them; and how many differ at the pixel itself.
struct Mismatch {
  int beyond_one_voxel = 0;
  int at_pixel = 0;
};
Mismatch Compare(const BallVolume& v, const WarpedSlice& slice, bool warped_truth) {
  Mismatch m;
  auto truth = [&](int a, int b) {
    const int axis = static_cast<int>(slice.axis);
    std::array<int, 3> ijk{};
    ijk[static_cast<size_t>(axis)] = slice.index;
    ijk[axis == 0 ? 1 : 0] = a;
    ijk[axis == 2 ? 1 : 2] = b;
    const Eigen::Vector3d p = v.grid.Position(ijk[0], ijk[1], ijk[2]);
    return v.Inside(warped_truth ? Inverse(p) : p);
  };
  for (int b = 0; b < slice.dims[1]; ++b)
    for (int a = 0; a < slice.dims[0]; ++a) {
      const bool bright = slice.values[static_cast<size_t>(a + slice.dims[0] * b)] > 500;
      if (bright == truth(a, b)) continue;
      ++m.at_pixel;
      bool near = false;
      for (int db = -1; db <= 1; ++db)
        for (int da = -1; da <= 1; ++da) {
          const int aa = a + da, bb = b + db;
          if (aa >= 0 && bb >= 0 && aa < slice.dims[0] && bb < slice.dims[1] && truth(aa, bb) == bright) near = true;
        }
      if (!near) ++m.beyond_one_voxel;
    }
  return m;
}

TEST(SliceWarpTest, MatchesTheAnalyticallyWarpedSliceWithinOneVoxel) {
  const BallVolume v = MakeBall();
  // A mesh covering the ball with room to spare, moved by the field.
  TetrahedralMesh mesh = MakeBoxTetMesh(Eigen::Vector3d::Constant(0.050), Eigen::Vector3i(8, 8, 8));
  mesh.vertices.rowwise() += Eigen::RowVector3d(0.015, 0.015, 0.015);
  Vertices deformed = mesh.vertices;
  for (Eigen::Index i = 0; i < deformed.rows(); ++i)
    deformed.row(i) = Forward(mesh.vertices.row(i).transpose()).transpose();

  const WarpedSlice slice = WarpSlice(v.grid, v.ct, mesh, deformed, SliceAxis::kK, 22);
  const Mismatch warped = Compare(v, slice, true);
  EXPECT_EQ(warped.beyond_one_voxel, 0);
  // The field moves the ball's outline by several voxels: the unwarped slice does not match.
  const WarpedSlice identity = WarpSlice(v.grid, v.ct, mesh, mesh.vertices, SliceAxis::kK, 22);
  EXPECT_EQ(Compare(v, identity, false).beyond_one_voxel, 0);
  EXPECT_GT(Compare(v, identity, true).beyond_one_voxel, 20);
  // Pixels in the deformed box are marked, the corner outside it is not.
  EXPECT_EQ(slice.in_mesh[static_cast<size_t>(20 + 40 * 20)], 1);
  EXPECT_EQ(slice.in_mesh[0], 0);
}

TEST(SliceWarpTest, OtherAxesAndBadInput) {
  const BallVolume v = MakeBall();
  const TetrahedralMesh mesh = MakeBoxTetMesh(Eigen::Vector3d::Constant(0.050), Eigen::Vector3i(4, 4, 4));
  for (SliceAxis axis : {SliceAxis::kI, SliceAxis::kJ}) {
    const WarpedSlice s = WarpSlice(v.grid, v.ct, mesh, mesh.vertices, axis, 20);
    EXPECT_EQ(Compare(v, s, false).at_pixel, 0);  // identity: the slice as it is
  }
  EXPECT_THROW(WarpSlice(v.grid, v.ct, mesh, mesh.vertices, SliceAxis::kK, 40), std::invalid_argument);
  EXPECT_THROW(WarpSlice(v.grid, {1, 2, 3}, mesh, mesh.vertices, SliceAxis::kK, 1), std::invalid_argument);
  EXPECT_THROW(WarpSlice(v.grid, v.ct, mesh, Vertices(3, 3), SliceAxis::kK, 1), std::invalid_argument);
}

}  // namespace
}  // namespace vesica::physics
