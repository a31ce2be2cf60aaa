#pragma once
// Internal elastic forces, tangent stiffness and strain energy of a FEM body at a displacement,
// linear or corotational (f_e = R K_e (R^T x_e - X_e), tangent R K_e R^T: the usual
// corotational linearisation that drops dR/dx).

#include <Eigen/Core>
#include <vector>

#include "physics/fem/fem_model.h"
#include "physics/fem/huge_page_allocator.h"

namespace vesica::physics {

/// The kernel a corotational pass with a rotation cache runs for `requested` on this CPU: kAuto
/// reads VESICA_FEM_ELEMENT_KERNEL once, else takes the widest supported; an unsupported request
/// falls back to the next narrower kernel. Never kAuto.
ElementKernel ResolveElementKernel(ElementKernel requested);

/// Products with the tangent K_t that a corotational pass leaves, y[k] = K_t x[k] (k < count; x's
/// entries taken as given, fixed dofs included): CorotationalTangentTimes's values, taken during
/// the vectorised pass (each tet's turned gradients still in registers: no pass of their own) or,
/// where the pass is scalar, after it. The rotation cache is required.
struct PassProducts {
  int count = 0;
  const Eigen::VectorXd* x[2] = {};
  Eigen::VectorXd* y[2] = {};
  void Add(const Eigen::VectorXd& in, Eigen::VectorXd& out) { x[count] = &in, y[count] = &out, ++count; }
};

/// u: 3n displacement (m). Writes the tangent values in pattern order (nnz, N/m; for a linear
/// body a copy of the constant K, skipped when tangent_values is null) and the internal force
/// (3n, N). Returns the elastic energy (J). rotation_cache (optional, per tet quaternion x y z w,
/// identity on first use) warm-starts the corotational rotation from the last call: far cheaper
/// than an SVD per element; elements near inversion still go through the SVD. With a cache the pass
/// runs model.settings.element_kernel (ResolveElementKernel). turned_gradients (optional, with a
/// cache): the SIMD pass leaves R grad N_b there for CorotationalTangentTimes (emptied otherwise).
/// largest_turn_rad (optional): the largest angle any tet turned since the cache was last written
/// (0 for a linear body, +inf for a corotational one without a cache). tangent_scale: the tangent
/// values are tangent_scale K_t (an implicit step's stiffness factor, applied in the SIMD pass's one
/// write of each value instead of another pass over them). products (optional, corotational with a
/// cache): PassProducts.
double ComputeElasticForces(const FemModel& model, const Eigen::VectorXd& u, Eigen::VectorXd* tangent_values,
                            Eigen::VectorXd* internal_force_N, std::vector<Eigen::Vector4d>* rotation_cache = nullptr,
                            HugePageVector<double>* turned_gradients = nullptr, double* largest_turn_rad = nullptr,
                            double tangent_scale = 1.0, const PassProducts* products = nullptr);

/// The tangent rounded to float in FloatBlockRows' layout (pcg_solver.h): its values and, per node
/// pair of model.tangent_blocks, the offsets FloatTangentRowOffsets gives.
struct FloatTangentRows {
  float* values = nullptr;
  const std::vector<int>* pair_offsets = nullptr;
};

/// Where pair p's block (b, a) and block (a, b) start in float rows whose pattern value index
/// `slot` lives at value_index_of_slots[slot] (FloatBlockRows::ValueIndexOfSlots).
std::vector<int> FloatTangentRowOffsets(const TangentBlocks& blocks, const std::vector<int>& value_index_of_slots);

/// True when ComputeElasticForces can write the tangent into float rows: a corotational body whose
/// element pass runs vectorised (the scalar and linear passes write the pattern's doubles).
bool FloatTangentAvailable(const FemModel& model);

/// ComputeElasticForces writing tangent_scale K_t into float rows instead of the pattern's doubles
/// (a preconditioner's copy of S, with no double copy made and rounded); every row value of the
/// pattern is written. Only when FloatTangentAvailable(model); rotation_cache required.
double ComputeElasticForcesFloatTangent(const FemModel& model, const Eigen::VectorXd& u,
                                        const FloatTangentRows& tangent, double tangent_scale,
                                        Eigen::VectorXd* internal_force_N, std::vector<Eigen::Vector4d>* rotation_cache,
                                        HugePageVector<double>* turned_gradients, double* largest_turn_rad,
                                        const PassProducts* products = nullptr);

/// y = K_t x for a corotational body without assembling K_t (the tangent ComputeElasticForces
/// assembles, R K R^T per tet, at the rotations it left in rotation_cache), element by element
/// with model.settings.element_kernel. Costs about one SpMV; saves the assembly when a solver only
/// needs products. x, y: 3n. turned_gradients: what the last pass left (same rotations), which
/// spares the SIMD product turning every tet's gradients; ignored when empty.
void CorotationalTangentTimes(const FemModel& model, const std::vector<Eigen::Vector4d>& rotation_cache,
                              const Eigen::VectorXd& x, Eigen::VectorXd& y,
                              const HugePageVector<double>* turned_gradients = nullptr);

/// y = A x for a symmetric matrix stored in the pattern (read row-wise, gather form).
void SymmetricPatternMultiply(const SparsePattern& pattern, const Eigen::VectorXd& values, const Eigen::VectorXd& x,
                              Eigen::VectorXd& y);

}  // namespace vesica::physics
