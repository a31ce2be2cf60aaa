#pragma once
// Internal to elastic_forces.cpp: the corotational element pass vectorised across tets (AVX-512:
// 8 tets a vector, AVX2: 4), compiled per instruction set (element_pass_avx512.cpp,
// element_pass_avx2.cpp share element_pass_kernel.inc) and chosen at run time, because the
// project builds without -march. Same rules and results as the scalar pass (to rounding): the
// warm-started Newton polar iteration per lane; a lane that needs Mueller's step or the SVD
// (det F <= 0.2) is redone by ScalarElementRotation from its cached quaternion.

namespace vesica::physics {

struct TangentBlocks;

struct ElementPassArgs {
  const double* rest = nullptr;  ///< ElementBatches::rest
  const int* dofs = nullptr;     ///< ElementBatches::dofs
  int num_tets = 0;
  double lambda_Pa = 0.0, mu_Pa = 0.0;
  const double* displacement = nullptr;  ///< u, 3n
  double* rotation_cache = nullptr;      ///< 4 per tet (x y z w), read and updated
  double* force = nullptr;               ///< 3n, zeroed by the caller, accumulated
  double* tangent = nullptr;             ///< nnz pattern values, all written; null: skip
  double tangent_scale = 1.0;            ///< tangent receives tangent_scale K_t
  /// With tangent: the model's node pairs (tangent_blocks.h) and a scratch array of
  /// kCornerVectorFields doubles a tet for the corner vectors the pairs are assembled from.
  const TangentBlocks* tangent_blocks = nullptr;
  double* corner_vectors = nullptr;
  /// Instead of `tangent`: the tangent rounded to float into FloatBlockRows' values (pcg_solver.h),
  /// pair p's K_ab column by column at tangent_row_offsets[2 p] (its block (b, a)) and row by row at
  /// tangent_row_offsets[2 p + 1] (block (a, b)); with tangent_blocks and corner_vectors.
  float* tangent_rows = nullptr;
  const int* tangent_row_offsets = nullptr;
  /// Turned shape gradients R grad N_b (b = 1..3, x y z) per tet in ElementBatches' block layout
  /// (kTurnedGradientFields fields a block): the pass writes them when non-null, the product reads
  /// them when non-null (else it turns the gradients by rotation_cache).
  double* turned_gradients_out = nullptr;
  const double* turned_gradients = nullptr;
  /// Pass only, optional: the smallest |q_before . q_after| over the tets, the cosine of half the
  /// largest turn since the rotation cache was last written.
  double* smallest_turn_cosine = nullptr;
  /// Pass only, optional: product_out[k] += K_t product_in[k] (k < num_products) at the pass's
  /// rotations, taken while each tet's turned gradients are in registers: the values
  /// TangentProduct gives from the turned gradients the pass leaves, without a pass of its own.
  int num_products = 0;
  const double* product_in[2] = {};
  double* product_out[2] = {};
};

/// The scalar pass's rotation rule for one element: the warm-started quaternion iteration where
/// det F > 0.2, else the SVD (q then set from R). F and R row-major 3x3; q x y z w, updated.
void ScalarElementRotation(const double* f, double* q, double* r);

/// Return the elastic energy (J); accumulate forces and tangent as ComputeElasticForces does.
double ElementPassAvx512(const ElementPassArgs& args);
double ElementPassAvx2(const ElementPassArgs& args);
/// force += K_t displacement element by element, R from rotation_cache (read only); tangent unused.
void TangentProductAvx512(const ElementPassArgs& args);
void TangentProductAvx2(const ElementPassArgs& args);

}  // namespace vesica::physics
