#pragma once
// The fat-and-fibrous layer of Calot's triangle: small volume cells filling a slab over the
// triangle (junction, neck, hilum) and a sleeve around each tube. Cautery (a dose of energy) and
// blunt dissection (the grasper's jaws pushing or spreading cells beyond a tearing strain)
// use up a cell's integrity; a removed cell no longer hides the tubes (docs/calot.md).

#include <Eigen/Core>
#include <array>
#include <vector>

#include "physics/calot/triangle_structures.h"

namespace vesica::physics::calot {

struct FatLayerDescription {
  /// The triangle's corners: the cystic duct's junction, the gallbladder's neck, the hilum (m).
  std::array<Eigen::Vector3d, 3> corners_m{Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
  double cell_spacing_m = 0.002;      ///< edge of a cell (a cube of the grid), > 0
  double slab_thickness_m = 0.006;    ///< the layer across the triangle's plane, > 0
  double sleeve_thickness_m = 0.002;  ///< fat around each tube beyond its wall, >= 0
  double density_kg_per_m3 = 950.0;   ///< fat with fibrous strands, > 0
  /// Energy that removes a kilogram of the layer by cautery (heating to 100 C and drying it out;
  /// docs/calot.md), J/kg, > 0.
  double ablation_energy_J_per_kg = 1.0e6;
  /// A cell pushed by this fraction of its size from where it sits tears loose: the strands to
  /// its neighbours, which stay, fail (its integrity is used up), > 0.
  double tear_strain = 0.5;
  /// Cells within this of a tube move with it (the sleeve and the triangle's edges), m, >= 0.
  double anchor_reach_m = 0.004;
  /// A tube point is hidden while an intact cell lies within the tube's radius plus this, m, > 0.
  double cover_margin_m = 0.002;
  double tube_sample_spacing_m = 0.0005;  ///< along each tube, for the uncovered fraction, > 0
};

/// The triangle from the description's tubes: the cystic duct's start (junction), the neck,
/// the common hepatic duct's start (hilum). Throws std::invalid_argument when a tube is missing.
FatLayerDescription DefaultFatLayerDescription(const TriangleDescription& triangle);

enum class FatCellState { kIntact, kBurnt, kTorn };

struct FatCell {
  Eigen::Vector3d p_Rest_W_m = Eigen::Vector3d::Zero();
  int anchor_tube = -1;  ///< tube it moves with, -1: none (the triangle's middle stays)
  double anchor_s_m = 0.0;
  Eigen::Vector3d p_AnchorRest_W_m = Eigen::Vector3d::Zero();
  bool in_triangle = false;  ///< in the triangle's slab (else only a sleeve)
  Eigen::Vector3d displacement_m =
      Eigen::Vector3d::Zero();  ///< pushed by instruments; stays (fat parts, not springs back)
  double dose_J = 0.0;
  double max_displacement_m = 0.0;
  FatCellState state = FatCellState::kIntact;
};

class FatLayer {
 public:
  /// Throws std::invalid_argument naming the field when the description is out of range.
  FatLayer(const FatLayerDescription& description, const TriangleStructures& structures);

  const FatLayerDescription& description() const { return description_; }
  const std::vector<FatCell>& cells() const { return cells_; }
  const std::vector<Eigen::Vector3d>& cell_positions_m() const { return positions_; }
  double CellRemovalEnergy_J() const;  ///< ablation energy of one cell: e rho spacing^3
  /// 1 - dose / removal energy - (largest displacement / spacing) / tear strain, clamped to [0, 1].
  double Integrity(int cell) const;

  /// Follows the tubes (anchored cells) and updates what hides them; after structures.Step.
  void Update(const TriangleStructures& structures);

  /// The hook's tip (a sphere) at power_W for dt_s: the energy is shared by the intact cells
  /// within radius_m of p (centres); a cell whose dose reaches its removal energy is burnt.
  /// Returns the cells removed by this call.
  int Burn(const Eigen::Vector3d& p_Hook_W_m, double radius_m, double power_W, double dt_s);
  /// A jaw tip (a sphere) pushes the intact cells out of itself; a cell pushed beyond the tear
  /// strain tears loose. Spreading is both jaws' tips moving apart. Returns cells torn.
  int Push(const Eigen::Vector3d& p_Tip_W_m, double radius_m);

  double RemovedFraction() const;  ///< of all cells
  double BurntFraction() const;
  double TornFraction() const;
  double TriangleClearedFraction() const;  ///< of the triangle's slab cells: what the critical view reads
  /// Fraction of the tube's length that no intact cell hides.
  double UncoveredFraction(int tube) const;

 private:
  void Remove(FatCell& cell, FatCellState why);

  FatLayerDescription description_;
  std::vector<FatCell> cells_;
  std::vector<Eigen::Vector3d> positions_;  // current centres
  struct TubeSample {
    int tube = 0;
    double s_m = 0.0;
    double radius_m = 0.0;
    std::vector<int> nearby_cells;  // cells that can hide it
    Eigen::Vector3d p_W_m = Eigen::Vector3d::Zero();
    bool hidden = true;
  };
  std::vector<TubeSample> samples_;
  std::vector<int> samples_per_tube_;
};

}  // namespace vesica::physics::calot
