#pragma once
// The tubes of Calot's triangle as rods, with what the instruments did to them: clips that ride
// on their material point, cuts that split a rod into two with free ends, and the flow of bile
// and blood that follows. The lead's scene feeds the gallbladder's neck each step and reads back
// the force the tubes pull it with (docs/calot.md).

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "physics/calot/triangle_description.h"
#include "physics/calot/tube_flow.h"
#include "physics/calot/tube_rod.h"

namespace vesica::physics::calot {

/// A clip across a tube at a material point: it occludes the tube there and moves with it.
struct ClipOnTube {
  int tube = 0;      ///< index into the description's tubes
  double s_m = 0.0;  ///< material coordinate, from the tube's patient's side
};

/// A cut through a tube at a material point.
struct CutTube {
  int tube = 0;
  double s_m = 0.0;
};

/// One rod of a tube: the whole tube, or a piece of it between cuts.
struct TubePiece {
  int tube = 0;
  TubeRod rod;
  bool starts_at_cut = false;  ///< its first node is an open end
  bool ends_at_cut = false;    ///< its last node is an open end
};

/// The point of a tube nearest an instrument's segment (jaws, blades, or a ray).
struct TubeHit {
  int tube = 0;
  double s_m = 0.0;                                      ///< material coordinate of the nearest point
  Eigen::Vector3d p_Tube_W_m = Eigen::Vector3d::Zero();  ///< on the centreline
  Eigen::Vector3d p_Tool_W_m = Eigen::Vector3d::Zero();  ///< on the instrument's segment
  double centreline_distance_m = 0.0;
  double surface_gap_m = 0.0;  ///< centreline distance minus the tube's outer radius (< 0: inside)
};

/// An open end that bleeds or leaks bile.
struct TubeLeak {
  int tube = 0;
  Fluid fluid = Fluid::kBile;
  double s_m = 0.0;
  bool patient_side = true;  ///< the stump on the hilum / junction / hepatic artery side
  Eigen::Vector3d p_W_m = Eigen::Vector3d::Zero();
};

enum class ToolActionResult {
  kDone,
  kOutsideTube,  ///< s is not strictly inside the tube (or too near its held ends)
  kAlreadyCut,   ///< a clip on a cut, or a cut on a cut
  kOnClip,       ///< a cut through a clip's titanium, or a clip onto a clip
};

class TriangleStructures {
 public:
  /// Throws std::invalid_argument (ValidateTriangleDescription) for a bad description.
  explicit TriangleStructures(const TriangleDescription& description);

  const TriangleDescription& description() const { return description_; }
  int num_tubes() const { return static_cast<int>(description_.tubes.size()); }
  double TubeLength_m(int tube) const;  ///< rest arc-length
  const std::vector<TubePiece>& pieces() const { return pieces_; }
  const std::vector<ClipOnTube>& clips() const { return clips_; }
  const std::vector<CutTube>& cuts() const { return cuts_; }

  /// One step of every rod: each neck-held end follows the neck's displacement from the
  /// description's p_Neck_W_m.
  void Step(const Eigen::Vector3d& p_Neck_W_m);
  /// The force the tubes pull the neck with, N (the sum of the coupling springs' forces): the
  /// scene applies it to the gallbladder's neck nodes.
  Eigen::Vector3d NeckForce_N() const;
  /// How stiff the tubes are to the neck's motion, N/m: each piece tied to the neck and held at
  /// its other end (not a cut stump) adds its coupling spring in series with its axial stiffness
  /// E A / L. The scene puts it in the gallbladder's implicit step, so that NeckForce_N, a step
  /// behind the neck's motion, stays stable.
  double NeckStiffness_N_per_m() const;

  /// Current centreline point at a material coordinate (clamped to the tube).
  Eigen::Vector3d PositionAt(int tube, double s_m) const;
  /// Its rest position.
  Eigen::Vector3d RestPositionAt(int tube, double s_m) const;

  /// The tube point nearest a segment [a, b] (a clip applier's or scissors' jaws, a ray from
  /// the tool tip); none when no tube is within max_gap_m of it (surface gap).
  std::optional<TubeHit> NearestToSegment(const Eigen::Vector3d& a_W_m, const Eigen::Vector3d& b_W_m,
                                          double max_gap_m) const;
  /// A tool tip (a sphere) pushes the tubes' capsules out of itself; returns the deepest
  /// penetration, m.
  double PushByTip(const Eigen::Vector3d& p_Tip_W_m, double tip_radius_m);

  /// A clip at the tube's material point. Clips stay where they are put for the session.
  ToolActionResult PlaceClip(int tube, double s_m);
  Eigen::Vector3d ClipPosition(int clip) const;
  /// Divides the tube at s: the rod splits into two with free ends; clips keep their sides.
  ToolActionResult Cut(int tube, double s_m);

  TubeFlowState FlowState(int tube) const;
  bool FluidAt(int tube, double s_m) const;     ///< bile or blood is there (a clip holds it back)
  bool FlowPasses(int tube, double s_m) const;  ///< it flows through there
  std::vector<TubeLeak> Leaks() const;          ///< every open end that fluid reaches
  bool Bleeding() const;                        ///< any leak of blood
  bool BileLeaking() const;                     ///< any leak of bile

  /// A clip's half-width along the tube (a medium titanium clip is about 1 mm wide, m): a cut
  /// closer than this to a clip hits the clip, two clips closer than twice this overlap.
  static constexpr double kClipHalfWidth_m = 0.0006;

 private:
  const TubePiece& PieceAt(int tube, double s_m) const;
  void CheckTube(int tube, const char* what) const;

  TriangleDescription description_;
  std::vector<double> lengths_m_;
  std::vector<RodPoints> rest_points_;  // per tube, the whole rod's rest nodes
  std::vector<std::vector<double>> rest_coordinates_;
  std::vector<TubePiece> pieces_;
  std::vector<ClipOnTube> clips_;
  std::vector<CutTube> cuts_;
};

}  // namespace vesica::physics::calot
