#pragma once
// A tube (duct or artery) as a discrete elastic rod: a chain of nodes with stretch and bending
// stiffness, lumped mass, mass-proportional damping and gravity, stepped by implicit Euler whose
// incremental potential Newton's method minimises (docs/calot.md has the equations).

#include <Eigen/Core>
#include <memory>
#include <vector>

#include "physics/calot/tube_material.h"

namespace vesica::physics::calot {

/// #nodes by 3 points, m.
using RodPoints = Eigen::Matrix<double, Eigen::Dynamic, 3>;

struct TubeRodSettings {
  double time_step_s = 0.005;  ///< h, > 0 (the dissection scene's step, physics/scene/dissection_settings.h)
  Eigen::Vector3d gravity_m_per_s2 = Eigen::Vector3d::Zero();  ///< zero in the scene (organs are carried)
  int solver_iterations = 4;  ///< most Newton iterations a step (fewer once converged), >= 1
  /// Spring that ties a coupled node to its moving target (the gallbladder's neck), N/m, > 0.
  double coupling_stiffness_N_per_m = 5000.0;
};

enum class NodeHold {
  kFree,
  kFixed,    ///< kinematic: follows SetHeldPosition (the hilum, the duodenum)
  kCoupled,  ///< tied by a spring to a target point that moves (the neck); reports the force
};

class TubeRod {
 public:
  /// rest_points_m: #N by 3, N >= 2, no two consecutive points closer than 1e-6 m. The rod starts
  /// at rest there. material_coordinates_m: N increasing arc-lengths along the original tube
  /// (empty: measured from the first point), kept by cuts so a clip or cut names a material point.
  TubeRod(const RodPoints& rest_points_m, std::vector<double> material_coordinates_m, const TubeMaterial& material,
          const TubeRodSettings& settings);
  /// A rod whose current state differs from its rest shape (a piece of a cut rod).
  TubeRod(const RodPoints& rest_points_m, const RodPoints& positions_m, const RodPoints& velocities_m_per_s,
          std::vector<double> material_coordinates_m, const TubeMaterial& material, const TubeRodSettings& settings);
  ~TubeRod();
  TubeRod(TubeRod&&) noexcept;
  TubeRod& operator=(TubeRod&&) noexcept;

  int num_nodes() const { return static_cast<int>(positions_.rows()); }
  const RodPoints& positions_m() const { return positions_; }
  const RodPoints& velocities_m_per_s() const { return velocities_; }
  const RodPoints& rest_points_m() const { return rest_points_; }
  const std::vector<double>& material_coordinates_m() const { return material_coordinates_; }
  const TubeMaterial& material() const { return material_; }
  const TubeRodSettings& settings() const { return settings_; }
  NodeHold hold(int node) const { return holds_.at(static_cast<std::size_t>(node)); }
  const std::vector<double>& node_masses_kg() const { return masses_; }

  /// Holds a node where it is now (kFixed); SetHeldPosition moves it kinematically.
  void HoldFixed(int node);
  void SetHeldPosition(int node, const Eigen::Vector3d& p_W_m);
  /// Ties a node to a target by the coupling spring (kCoupled); SetCouplingTarget moves the target.
  void CoupleToTarget(int node, const Eigen::Vector3d& p_Target_W_m);
  void SetCouplingTarget(int node, const Eigen::Vector3d& p_Target_W_m);
  Eigen::Vector3d coupling_target_m(int node) const;
  /// Force the rod exerts on the coupled target (pulls it toward the node), N: k (x_node - target).
  Eigen::Vector3d CouplingForceOnTarget_N(int node) const;
  void Release(int node);  ///< back to kFree

  /// A force held on a node until changed (a test's tip load, an instrument's push), N.
  void SetExternalForce(int node, const Eigen::Vector3d& force_N);
  void ClearExternalForces();

  /// One implicit Euler step of settings().time_step_s.
  void Step();

  /// Pushes the rod's capsules (radius = outer radius) out of a sphere (a tool tip): free nodes of
  /// each penetrated segment move along the contact normal, their velocities take the motion.
  /// Returns the deepest penetration found before the push, m (0: no contact).
  double PushOutOfSphere(const Eigen::Vector3d& p_Centre_W_m, double radius_m);

  /// Point at material coordinate s (clamped to the rod's range), linear between nodes.
  Eigen::Vector3d PositionAt(double s_m) const;
  /// Index i of the segment [i, i+1] holding s (clamped), and the fraction along it.
  std::pair<int, double> SegmentAt(double s_m) const;
  double start_coordinate_m() const { return material_coordinates_.front(); }
  double end_coordinate_m() const { return material_coordinates_.back(); }

  double StretchEnergy_J() const;
  double BendingEnergy_J() const;
  double KineticEnergy_J() const;
  /// -sum m g.x: with the elastic energies, what a rod without input or coupling may not gain.
  double GravityPotential_J() const;
  /// Coupling springs' energy, 1/2 k |x - target|^2.
  double CouplingEnergy_J() const;

  /// Rest lengths of the N-1 segments, m.
  const std::vector<double>& rest_lengths_m() const { return rest_lengths_; }

 private:
  struct Solver;
  void Initialise();
  void Factorise();
  Eigen::Vector3d BendingTarget(int node, const RodPoints& x) const;

  RodPoints rest_points_, positions_, velocities_, external_forces_N_, coupling_targets_;
  std::vector<double> material_coordinates_;
  TubeMaterial material_;
  TubeRodSettings settings_;
  std::vector<NodeHold> holds_;
  std::vector<double> masses_, rest_lengths_, stretch_weights_, bending_weights_;
  RodPoints rest_curvature_;        // v0_i at interior nodes (rows 0 and N-1 unused)
  RodPoints rest_tangents_;         // unit tangent at interior nodes, rest
  std::unique_ptr<Solver> solver_;  // the Hessian's factorisation
};

}  // namespace vesica::physics::calot
