#pragma once
// Settings of the constraint-based registration (seed sections 3.2-3.4). The FEM body's own
// settings (material, time step, solver) travel in FemSettings; these are the registration's.

namespace vesica::physics {

struct RegistrationSettings {
  /// Pair a control point only with triangles whose inward normal agrees with the point's:
  /// n_triangle . n_c >= min_normal_cosine (section 3.3, Fig. 2(c)-(d)). false: nearest triangle
  /// whatever its side (Fig. 2(a)-(b), kept to show what the check prevents).
  bool check_normals = true;
  /// In [-1, 1]; 0 accepts any triangle facing the same half-space as the point's normal.
  double min_normal_cosine = 0.0;
  /// A control point farther than this from every eligible triangle is left out of the step
  /// (tracking lost); metres, > 0.
  double max_pairing_distance_m = 0.05;
  /// Soft constraints (eq. 6): W_soft_ii = soft_compliance_m_per_N (1 - c_i) / c_i for a point of
  /// confidence c_i: a fully trusted point (c = 1) is a hard constraint, an untrusted one gives
  /// way. 0: every constraint hard whatever its confidence. m/N, >= 0.
  double soft_compliance_m_per_N = 0.0;
  /// Quasi-static registration (eqs. 1-3 without inertia carried over): the velocity is cleared
  /// after each step, so the body settles into the configuration of least elastic energy that
  /// meets the constraints instead of oscillating about it.
  bool quasi_static = true;
};

}  // namespace vesica::physics
