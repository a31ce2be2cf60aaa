// The dispatched SIMD element pass (element_pass_avx2.cpp / element_pass_avx512.cpp) against the
// scalar pass: forces, tangent values, energy and rotations on deformed meshes with inverted,
// near-inverted and strongly turned elements, tet counts that are not a multiple of the vector
// width, and whole-body steps.

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <random>

#include "physics/fem/elastic_forces.h"
#include "physics/fem/fem_body.h"
#include "physics/fem/pcg_solver.h"
#include "tests/fem/fem_test_support.h"

namespace vesica::physics {
namespace {

using testing::Clamp;
using testing::GallbladderNewmarkSettings;
using testing::NodesOnPlane;

FemModel Box(const Eigen::Vector3i& cells, ElementKernel kernel) {
  FemSettings s;
  s.material = {2300.0, 0.45, 1000.0};
  s.element_kernel = kernel;
  return BuildFemModel(MakeBoxTetMesh({0.08, 0.03, 0.03}, cells), s, {});
}

// A rigid turn by `angle` about (1, 2, 0.5), a bend, and random nodal noise of `noise` times the
// shortest cell edge: large enough noise inverts some elements.
Eigen::VectorXd Deformation(const FemModel& m, const Eigen::Vector3i& cells, double angle, double noise, unsigned seed) {
  const Eigen::Matrix3d r = Eigen::AngleAxisd(angle, Eigen::Vector3d(1, 2, 0.5).normalized()).toRotationMatrix();
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const double cell = std::min({0.08 / cells.x(), 0.03 / cells.y(), 0.03 / cells.z()});
  Eigen::VectorXd u(m.num_dofs());
  for (int i = 0; i < m.num_nodes(); ++i) {
    const Eigen::Vector3d x = m.rest_mesh.vertices.row(i);
    const Eigen::Vector3d bent = x + Eigen::Vector3d(0.0, 3.0 * x.x() * x.x(), 0.1 * x.x());
    u.segment<3>(3 * i) = r * bent - x + noise * cell * Eigen::Vector3d(unit(rng), unit(rng), unit(rng));
  }
  return u;
}

struct PassResult {
  double energy = 0.0;
  Eigen::VectorXd force, tangent;
  std::vector<Eigen::Vector4d> cache;
};

PassResult RunPass(const FemModel& m, const Eigen::VectorXd& u, std::vector<Eigen::Vector4d> cache) {
  PassResult p;
  p.cache = std::move(cache);
  p.energy = ComputeElasticForces(m, u, &p.tangent, &p.force, &p.cache);
  return p;
}

double MaxRelative(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  return (a - b).cwiseAbs().maxCoeff() / b.cwiseAbs().maxCoeff();
}

// Largest difference of the rotation matrices of the two caches (q and -q are the same turn).
double MaxRotationDifference(const std::vector<Eigen::Vector4d>& a, const std::vector<Eigen::Vector4d>& b) {
  double worst = 0.0;
  for (size_t t = 0; t < a.size(); ++t) {
    const Eigen::Matrix3d ra = Eigen::Quaterniond(a[t]).toRotationMatrix();
    const Eigen::Matrix3d rb = Eigen::Quaterniond(b[t]).toRotationMatrix();
    worst = std::max(worst, (ra - rb).cwiseAbs().maxCoeff());
  }
  return worst;
}

std::vector<ElementKernel> SimdKernelsOfThisCpu() {
  std::vector<ElementKernel> kernels;
  for (ElementKernel k : {ElementKernel::kAvx2, ElementKernel::kAvx512})
    if (ResolveElementKernel(k) == k) kernels.push_back(k);
  return kernels;
}

const char* Name(ElementKernel k) { return k == ElementKernel::kAvx512 ? "avx512" : "avx2"; }

TEST(ElementPassSimdTest, ResolvesToAKernelThisCpuRuns) {
  EXPECT_EQ(ResolveElementKernel(ElementKernel::kScalar), ElementKernel::kScalar);
  const ElementKernel automatic = ResolveElementKernel(ElementKernel::kAuto);
  EXPECT_NE(automatic, ElementKernel::kAuto);
  // A wider request than the CPU supports comes back narrower, never wider than kAuto's choice
  // without an environment override.
  const ElementKernel widest = ResolveElementKernel(ElementKernel::kAvx512);
  EXPECT_LE(static_cast<int>(widest), static_cast<int>(ElementKernel::kAvx512));
  if (!std::getenv("VESICA_FEM_ELEMENT_KERNEL")) {
    EXPECT_EQ(automatic, widest);
  }
  if (SimdKernelsOfThisCpu().empty()) GTEST_SKIP() << "no AVX2/AVX-512 on this CPU: only the scalar pass runs";
}

// Random deformed meshes: a cold call from identity rotations (turns of up to 2.6 rad: the Newton
// system is indefinite there, so lanes go through Mueller's step), then warm-started calls as the
// mesh turns further; noise that inverts some elements (the SVD lanes). 30 and 126 tets: not a
// multiple of 4 or 8. Every output must be the scalar pass's to rounding.
TEST(ElementPassSimdTest, MatchesTheScalarPassOnDeformedMeshesWithInvertedElements) {
  const auto kernels = SimdKernelsOfThisCpu();
  if (kernels.empty()) GTEST_SKIP() << "no AVX2/AVX-512 on this CPU";
  for (const Eigen::Vector3i& cells : {Eigen::Vector3i(5, 1, 1), Eigen::Vector3i(7, 3, 1), Eigen::Vector3i(8, 3, 3)}) {
    const FemModel scalar = Box(cells, ElementKernel::kScalar);
    const int tets = scalar.rest_mesh.num_tets();
    for (ElementKernel kernel : kernels) {
      const FemModel simd = Box(cells, kernel);
      std::vector<Eigen::Vector4d> cache_scalar, cache_simd;
      int inverted = 0, near_inverted = 0;
      double worst[4] = {};
      for (int call = 0; call < 4; ++call) {
        const double angle = 1.2 + 0.7 * call;  // 1.2, 1.9, 2.6, 3.3 rad
        const Eigen::VectorXd u = Deformation(scalar, cells, angle, call == 3 ? 0.05 : 0.6, 17u + call);
        for (int t = 0; t < tets; ++t) {
          Eigen::Matrix3d ds;
          Eigen::Vector3d x[4];
          for (int a = 0; a < 4; ++a) {
            const int n = scalar.rest_mesh.tets(t, a);
            x[a] = scalar.rest_mesh.vertices.row(n).transpose() + u.segment<3>(3 * n);
          }
          ds << x[1] - x[0], x[2] - x[0], x[3] - x[0];
          const double det = (ds * scalar.elements[t].rest_shape_inverse).determinant();
          inverted += det < 0.0;
          near_inverted += det >= 0.0 && det < 0.2;
        }
        PassResult a = RunPass(scalar, u, cache_scalar);
        PassResult b = RunPass(simd, u, cache_simd);
        const double force_error = MaxRelative(b.force, a.force), tangent_error = MaxRelative(b.tangent, a.tangent);
        const double energy_error = std::abs(b.energy - a.energy) / a.energy;
        const double rotation_error = MaxRotationDifference(b.cache, a.cache);
        worst[0] = std::max(worst[0], force_error), worst[1] = std::max(worst[1], tangent_error);
        worst[2] = std::max(worst[2], energy_error), worst[3] = std::max(worst[3], rotation_error);
        EXPECT_LT(force_error, 1e-12) << Name(kernel) << ", " << tets << " tets, call " << call;
        EXPECT_LT(tangent_error, 1e-12) << Name(kernel) << ", " << tets << " tets, call " << call;
        EXPECT_LT(energy_error, 1e-12) << Name(kernel) << ", " << tets << " tets, call " << call;
        EXPECT_LT(rotation_error, 1e-12) << Name(kernel) << ", " << tets << " tets, call " << call;
        // The assembled tangent is exactly symmetric (the scalar one only to rounding).
        const Eigen::Map<const Eigen::SparseMatrix<double>> k = PatternMatrix(simd.pattern, b.tangent);
        EXPECT_EQ((Eigen::SparseMatrix<double>(k) - Eigen::SparseMatrix<double>(k.transpose())).norm(), 0.0);
        // Run to run: bit-identical (no threads, fixed order of accumulation).
        PassResult again = RunPass(simd, u, cache_simd);
        EXPECT_EQ(std::memcmp(again.force.data(), b.force.data(), sizeof(double) * b.force.size()), 0);
        EXPECT_EQ(std::memcmp(again.tangent.data(), b.tangent.data(), sizeof(double) * b.tangent.size()), 0);
        EXPECT_EQ(again.energy, b.energy);
        cache_scalar = std::move(a.cache);
        cache_simd = std::move(b.cache);
      }
      std::printf("%s, %d tets (%d inverted, %d with det F < 0.2 over 4 calls): max relative difference from "
                  "scalar: force %.1e, tangent %.1e, energy %.1e, rotation %.1e\n",
                  Name(kernel), tets, inverted, near_inverted, worst[0], worst[1], worst[2], worst[3]);
      // The scenes do exercise the fallback lanes.
      EXPECT_GT(inverted, 0) << tets << " tets";
      EXPECT_GT(near_inverted, 0) << tets << " tets";
    }
  }
}

// The SIMD pass against the analytic property the scalar one has: a rigid turn gives no force.
TEST(ElementPassSimdTest, RigidTurnGivesNoForceAndNoEnergy) {
  for (ElementKernel kernel : SimdKernelsOfThisCpu()) {
    const FemModel m = Box({5, 2, 3}, kernel);  // 180 tets
    const Eigen::Matrix3d r = Eigen::AngleAxisd(0.9, Eigen::Vector3d(0.3, -1, 2).normalized()).toRotationMatrix();
    Eigen::VectorXd u(m.num_dofs());
    for (int i = 0; i < m.num_nodes(); ++i) {
      const Eigen::Vector3d x = m.rest_mesh.vertices.row(i);
      u.segment<3>(3 * i) = r * x - x;
    }
    std::vector<Eigen::Vector4d> cache;
    Eigen::VectorXd f, k;
    for (int call = 0; call < 2; ++call) {  // cold, then warm
      const double e = ComputeElasticForces(m, u, &k, &f, &cache);
      EXPECT_LT(f.cwiseAbs().maxCoeff(), 1e-9 * 2300.0 * 1e-6) << Name(kernel);
      EXPECT_LT(std::abs(e), 1e-15) << Name(kernel);
    }
  }
}

// The tangent written straight into float rows is the double tangent rounded (FloatBlockRows'
// Update of it), bit for bit, at a scale, with the same forces, energy, rotations and turn: on a
// deformed mesh with inverted elements, cold and warm, 126 tets (not a multiple of 8).
TEST(ElementPassSimdTest, FloatRowTangentIsTheRoundedDoubleTangent) {
  if (!FloatBlockRows::available()) GTEST_SKIP() << "no AVX2 + FMA (or VESICA_FEM_ELEMENT_KERNEL=scalar)";
  for (ElementKernel kernel : SimdKernelsOfThisCpu()) {
    const Eigen::Vector3i cells(7, 3, 1);
    const FemModel m = Box(cells, kernel);
    ASSERT_TRUE(FloatTangentAvailable(m));
    FloatBlockRows expected, written;
    written.Reshape(m.pattern);
    const std::vector<int> offsets = FloatTangentRowOffsets(m.tangent_blocks, written.ValueIndexOfSlots(m.pattern));
    std::vector<Eigen::Vector4d> cache_double, cache_float;
    for (double angle : {0.4, 0.7}) {
      const Eigen::VectorXd u = Deformation(m, cells, angle, 0.4, 11);
      Eigen::VectorXd tangent, force_double, force_float;
      double turn_double = 0.0, turn_float = 0.0;
      const double scale = 3.7;
      const double e_double =
          ComputeElasticForces(m, u, &tangent, &force_double, &cache_double, nullptr, &turn_double, scale);
      const double e_float = ComputeElasticForcesFloatTangent(m, u, {written.values(), &offsets}, scale, &force_float,
                                                              &cache_float, nullptr, &turn_float);
      expected.Update(m.pattern, tangent);
      const auto count = m.pattern.structure.nonZeros();
      int differing = 0;
      for (Eigen::Index k = 0; k < count; ++k) differing += expected.values()[k] != written.values()[k];
      EXPECT_EQ(differing, 0) << Name(kernel) << " angle " << angle;
      EXPECT_EQ(e_double, e_float);
      EXPECT_EQ((force_double - force_float).cwiseAbs().maxCoeff(), 0.0);
      EXPECT_EQ(MaxRotationDifference(cache_double, cache_float), 0.0);
      EXPECT_EQ(turn_double, turn_float);
    }
  }
}

// The pass reports the largest turn of any tet since the rotation cache was written: a rigid turn
// of 0.9 rad from the rest cache, none when repeated, then 0.4 rad more (about another axis) on
// top of it; every kernel alike, and the SIMD kernels agree with the scalar one on a mesh with
// inverted elements (whose lanes take the scalar rule). A linear body never turns.
TEST(ElementPassSimdTest, ReportsTheLargestTurnSinceTheCacheWasWritten) {
  std::vector<ElementKernel> kernels = SimdKernelsOfThisCpu();
  kernels.push_back(ElementKernel::kScalar);
  const Eigen::Matrix3d first = Eigen::AngleAxisd(0.9, Eigen::Vector3d(0.3, -1, 2).normalized()).toRotationMatrix();
  const Eigen::Matrix3d second =
      Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, 0.5, 0).normalized()).toRotationMatrix() * first;
  for (ElementKernel kernel : kernels) {
    const FemModel m = Box({5, 2, 3}, kernel);  // 180 tets: not a multiple of 8
    auto turned = [&](const Eigen::Matrix3d& r) {
      Eigen::VectorXd u(m.num_dofs());
      for (int i = 0; i < m.num_nodes(); ++i) {
        const Eigen::Vector3d x = m.rest_mesh.vertices.row(i);
        u.segment<3>(3 * i) = r * x - x;
      }
      return u;
    };
    const char* name = kernel == ElementKernel::kScalar ? "scalar" : Name(kernel);
    std::vector<Eigen::Vector4d> cache;
    Eigen::VectorXd f;
    double turn = -1.0;
    ComputeElasticForces(m, turned(first), nullptr, &f, &cache, nullptr, &turn);
    EXPECT_NEAR(turn, 0.9, 1e-7) << name;
    ComputeElasticForces(m, turned(first), nullptr, &f, &cache, nullptr, &turn);
    EXPECT_NEAR(turn, 0.0, 1e-7) << name;
    ComputeElasticForces(m, turned(second), nullptr, &f, &cache, nullptr, &turn);
    EXPECT_NEAR(turn, 0.4, 1e-7) << name;
    ComputeElasticForces(m, turned(second), nullptr, &f, nullptr, nullptr, &turn);
    EXPECT_TRUE(std::isinf(turn)) << name << ": without a cache the turn is unknown";
  }
  // Inverted and near-inverted elements: the SIMD kernels' scalar lanes report their turns too.
  const Eigen::Vector3i cells(7, 3, 3);
  const FemModel scalar = Box(cells, ElementKernel::kScalar);
  for (ElementKernel kernel : SimdKernelsOfThisCpu()) {
    const FemModel simd = Box(cells, kernel);
    std::vector<Eigen::Vector4d> scalar_cache, simd_cache;
    Eigen::VectorXd f;
    double scalar_turn = 0.0, simd_turn = 0.0;
    for (double noise : {0.2, 0.9}) {
      const Eigen::VectorXd u = Deformation(scalar, cells, 1.3, noise, 7);
      ComputeElasticForces(scalar, u, nullptr, &f, &scalar_cache, nullptr, &scalar_turn);
      ComputeElasticForces(simd, u, nullptr, &f, &simd_cache, nullptr, &simd_turn);
      EXPECT_GT(simd_turn, 0.1) << Name(kernel) << " noise " << noise;
      EXPECT_NEAR(simd_turn, scalar_turn, 1e-6) << Name(kernel) << " noise " << noise;
    }
  }
  FemSettings linear;
  linear.material = {2300.0, 0.45, 1000.0};
  linear.element_model = ElementModel::kLinear;
  const FemModel m = BuildFemModel(MakeBoxTetMesh({0.08, 0.03, 0.03}, {3, 2, 2}), linear, {});
  Eigen::VectorXd f;
  double turn = -1.0;
  ComputeElasticForces(m, Eigen::VectorXd::Constant(m.num_dofs(), 0.01), nullptr, &f, nullptr, nullptr, &turn);
  EXPECT_EQ(turn, 0.0);
}

// Whole bodies: the twisted, pulled box of FemBodyTest stepped with the scalar and the SIMD pass,
// exact CHOLMOD steps and rotated-factor PCG with Gauss-Seidel sweeps (the scene's solver).
TEST(ElementPassSimdTest, BodyStepsMatchTheScalarPass) {
  const auto kernels = SimdKernelsOfThisCpu();
  if (kernels.empty()) GTEST_SKIP() << "no AVX2/AVX-512 on this CPU";
  const TetrahedralMesh mesh = MakeBoxTetMesh({0.08, 0.03, 0.03}, {8, 3, 3});
  const std::vector<int> free_end = NodesOnPlane(mesh, 0, 0.08);
  for (LinearSolverKind solver : {LinearSolverKind::kCholmod, LinearSolverKind::kRotatedFactorPcg}) {
    std::vector<Eigen::VectorXd> reference;
    for (ElementKernel kernel : {ElementKernel::kScalar, kernels.back()}) {
      FemSettings s = GallbladderNewmarkSettings(solver);
      s.rotated_factor_gauss_seidel = true;
      s.pcg_relative_tolerance = 1e-12;
      s.pcg_max_iterations = 200;
      s.element_kernel = kernel;
      auto model = std::make_shared<FemModel>(BuildFemModel(mesh, s, Clamp(NodesOnPlane(mesh, 0, 0.0))));
      FemBody body(model);
      double max_difference = 0.0, max_displacement = 0.0;
      for (int step = 0; step < 60; ++step) {
        Eigen::VectorXd f = Eigen::VectorXd::Zero(model->num_dofs());
        for (int n : free_end) {
          const Eigen::Vector3d x = mesh.vertices.row(n).transpose() + body.state().displacement_m.segment<3>(3 * n);
          f.segment<3>(3 * n) = 0.2 * Eigen::Vector3d::UnitX().cross(x - Eigen::Vector3d(0.08, 0.015, 0.015));
        }
        body.SetExternalForces(f);
        const StepReport r = body.Step();
        ASSERT_TRUE(r.accepted) << r.rejection_reason;
        const Eigen::VectorXd& u = body.state().displacement_m;
        if (kernel == ElementKernel::kScalar) {
          reference.push_back(u);
          continue;
        }
        max_difference = std::max(max_difference, (u - reference[step]).cwiseAbs().maxCoeff());
        max_displacement = std::max(max_displacement, reference[step].cwiseAbs().maxCoeff());
      }
      if (kernel == ElementKernel::kScalar) continue;
      std::printf("%s steps, %s vs scalar pass: max |u| %.4f m, max difference %.2e m\n",
                  solver == LinearSolverKind::kCholmod ? "CHOLMOD" : "rotated-factor PCG", Name(kernel),
                  max_displacement, max_difference);
      EXPECT_GT(max_displacement, 0.005);
      EXPECT_LT(max_difference, 1e-10 * max_displacement);
    }
  }
}

}  // namespace
}  // namespace vesica::physics
