#pragma once
// Scenario settings of one FEM body: element model, mass, damping, integrator and linear solver.

#include <string>

#include "physics/fem/elastic_material.h"

namespace vesica::physics {

enum class ElementModel {
  kLinear,        ///< small-strain Hooke; K constant
  kCorotational,  ///< per-element rotation removed before Hooke (registration paper 3.2)
};

enum class MassModel { kLumped, kConsistent };

enum class TimeIntegrator {
  kNewmark,        ///< Newmark-beta (gallbladder paper eqs. 6-7); beta 1/4, gamma 1/2 conserve energy
  kBackwardEuler,  ///< implicit Euler: unconditionally stable, damps as 1/sqrt(1 + (omega h)^2)
};

enum class LinearSolverKind {
  kPcg,      ///< conjugate gradient, block-Jacobi preconditioned (the paper's PCG)
  kCholmod,  ///< sparse Cholesky (SuiteSparse CHOLMOD); see cholmod_refresh_steps
  /// PCG on the step's system, preconditioned by a CHOLMOD factor of the rest system S0 (factorised
  /// once, again only when the attachment springs change) turned into the current frame per node:
  /// z = R S0^-1 R^T r, R the nodes' rotations averaged from their elements' (warped stiffness as
  /// a preconditioner). Converges in a few iterations under large rotations; pcg_relative_tolerance
  /// and pcg_max_iterations apply. See rotated_factor_single_precision and
  /// rotated_factor_gauss_seidel; docs/performance/fem.md has the measured trade-offs.
  kRotatedFactorPcg,
};

/// Instruction set of the corotational element pass (rotations, forces, tangent). The SIMD kernels
/// give the scalar results to rounding (~1e-13 relative) and are bit-identical run to run on one
/// machine; kAuto takes the widest the CPU supports unless the environment variable
/// VESICA_FEM_ELEMENT_KERNEL names one (scalar, avx2, avx512). A kernel the CPU lacks falls back
/// to the next narrower one. Linear bodies and passes without a rotation cache are always scalar.
enum class ElementKernel { kAuto, kScalar, kAvx2, kAvx512 };

struct FemSettings {
  std::string body_name = "fem body";  ///< used in every error message
  ElasticMaterial material;
  ElementModel element_model = ElementModel::kCorotational;
  MassModel mass_model = MassModel::kLumped;
  TimeIntegrator integrator = TimeIntegrator::kBackwardEuler;
  LinearSolverKind solver = LinearSolverKind::kCholmod;

  double time_step_s = 1e-2;          ///< h, s; > 0
  double rayleigh_mass_per_s = 0.0;   ///< alpha in D = alpha M + beta K, 1/s; >= 0
  double rayleigh_stiffness_s = 0.0;  ///< beta in D = alpha M + beta K, s; >= 0
  double newmark_beta = 0.25;         ///< 0 < beta <= 0.5, and 2 beta >= gamma (unconditionally stable)
  double newmark_gamma = 0.5;         ///< 0.5 <= gamma <= 1

  double pcg_relative_tolerance = 1e-8;  ///< stop when |r| <= tol |b| (paper: 1e-8)
  int pcg_max_iterations = 20;           ///< paper: 20
  /// Corotational + CHOLMOD: refactorise the system every this many steps (1 = every step, exact);
  /// in between, the last factor preconditions PCG. Linear bodies factorise once.
  int cholmod_refresh_steps = 1;
  /// kRotatedFactorPcg: apply the rest factor rounded to float (half the memory traffic of the
  /// memory-bound solve; PCG still converges to pcg_relative_tolerance, in about as many
  /// iterations). false: the double factor (a linear body then converges in exactly one iteration).
  bool rotated_factor_single_precision = true;
  /// kRotatedFactorPcg with rotated_factor_single_precision: store the factor as IEEE half (times a
  /// power of two) instead of float, solved in float: half the bytes again, about the same
  /// iterations (a preconditioner needs no more digits). Needs F16C; float without it.
  bool rotated_factor_half_precision = true;
  /// kRotatedFactorPcg: wrap the rotated factor in a forward and a backward block Gauss-Seidel
  /// sweep on the true system (symmetric multiplicative, still SPD): the sweeps remove the local
  /// error where element rotations differ from their nodes' (a grasped, sheared corner).
  bool rotated_factor_gauss_seidel = false;
  /// rotated_factor_gauss_seidel: forward sweeps before the rotated factor and backward sweeps after
  /// it (as many of each; still symmetric). Each forward sweep after the first starts from the
  /// residual the previous one leaves (-U times its correction, from the same pass). >= 1. On the
  /// 2,865-node gallbladder, with the local solves, 2 sweeps take 5.13 iterations instead of 5.38
  /// and a dearer step (7.25 against 6.6-6.9 ms): one is the fastest.
  int rotated_factor_sweeps = 1;
  /// kRotatedFactorPcg, attachments changed (connective tissue cut) after the first step: the rest
  /// factor is refactorised on a worker thread and adopted this many steps later (a fixed step, so
  /// runs stay bit-identical); meanwhile the old factor preconditions the new system (a few more
  /// iterations after a spring cut; a change as large as the springs themselves can need more than
  /// pcg_max_iterations). A factorisation costs ~30 ms at 1,000 nodes: in the step, it stalls a
  /// real-time scene. 0: refactorise in the next step. >= 0.
  int rotated_factor_adopt_steps = 15;
  /// rotated_factor_gauss_seidel: sweep a float copy of the system matrix stored in node-block rows
  /// (FloatBlockRows: a third of the bytes the sweeps stream; PCG's own products stay double, so the
  /// residual still reaches pcg_relative_tolerance). Needs AVX2 + FMA; the double matrix without.
  bool rotated_factor_float_sweeps = true;
  /// kRotatedFactorPcg, corotational: PCG's products with S (and the damping drive's K_t v) element
  /// by element from the turned gradients the element pass leaves (R K R^T per tet; 0.10 ms against
  /// an assembled SpMV's 0.13 ms at 2,865 nodes) instead of from the assembled S. Without the
  /// Gauss-Seidel sweeps S is then never assembled; with them it still is, every step, for the
  /// sweeps, their block inverses and the local solves, but no product reads it. Same steps to
  /// rounding.
  bool rotated_factor_matrix_free = true;
  /// kRotatedFactorPcg on an assembled system (the Gauss-Seidel variant, or matrix_free off): solve
  /// exactly, before and after the rotated factor, on the nodes whose tets turn least alike
  /// (LocalBlockCorrection: a dense Cholesky of S there, each step), where the turned rest factor
  /// is poorest (a grasped node, a sharp bend): this share of the body's nodes, rounded, at most
  /// rotated_factor_local_nodes_max. On the gallbladder box (docs/performance/fem.md, round 7) the
  /// fastest counts were ~1/60 of the nodes: 16 of 980, 32 of 2,000, 48 of 2,900 (8.3 -> 5.9
  /// iterations a step); at 300 nodes the 5 nodes neither help nor cost. In [0, 1]; 0: none.
  double rotated_factor_local_share = 1.0 / 60.0;
  /// The dense factorisation grows as the cube of the count: on the 2,900-node box 64 and 96 nodes
  /// made the step slower than 48 (6.7-6.8 and 7.1-7.3 against 6.4 ms over 100 steps). >= 0.
  int rotated_factor_local_nodes_max = 64;
  /// kRotatedFactorPcg: the nodes' rotations that turn the rest factor (a volume-weighted mean of
  /// their tets' quaternions, a pass over every node's tets) are recomputed once the tets may have
  /// turned this much since (the sum over element passes of the largest turn of any tet); they
  /// only shape the preconditioner, so stale ones cost iterations, never accuracy. 0: every step.
  /// >= 0, radians. The falling SOFA beam's nodes turn up to 0.006 rad a step: 0.02 recomputes them
  /// 33 times in 200 steps (1.010 -> 1.025 iterations at residual 1e-6, 1.32 -> 1.38 at 1e-8; 0.1
  /// ms a step less at both, where 0.03 gained more at 1e-6 and nothing at 1e-8); the pulled
  /// gallbladder box's turn 0.01-0.3 rad a step, recomputed 99 times in 100 steps (same
  /// iterations). docs/performance/fem.md, round 8.
  double rotated_factor_rotation_refresh_rad = 0.02;
  ElementKernel element_kernel = ElementKernel::kAuto;

  /// Divergence guard: a step is rejected when its energy exceeds this factor times (energy
  /// before + |work of external forces|) plus energy_floor_J, or this factor times (the energy at
  /// the body's first step + the |work| done on it since, SetState's jumps included) plus
  /// energy_floor_J: the second bound stops energy pumped up a little every step.
  double max_energy_growth = 10.0;
  double energy_floor_J = 1e-12;
};

/// Throws FemError naming the body and the field for out-of-range settings (material included).
/// BuildFemModel also refuses settings whose step system overflows its solver's range.
void ValidateSettings(const FemSettings& settings);

/// True when a body with these settings applies its tangent (and S) element by element in its
/// products: corotational, kRotatedFactorPcg, rotated_factor_matrix_free.
bool ProductsAreMatrixFree(const FemSettings& settings);

/// True when such a body also never assembles its tangent: ProductsAreMatrixFree without the
/// Gauss-Seidel sweeps (which need S).
bool TangentIsMatrixFree(const FemSettings& settings);

}  // namespace vesica::physics
