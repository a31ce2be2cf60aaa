#pragma once
// ChainMail (seed section 4.2, eqs. 3-8; Gibson 1997): linked elements that move a neighbour
// only when a link leaves its bounds, and then by the least amount that brings it back.
//
// A link joins element a to element b whose rest offset is `step` (a lattice step, each coordinate
// 0 or +-spacing). Along each coordinate c where the link extends (step_c != 0) the offset may
// shrink to gamma (compression, < 1) and grow to lambda (stretch, > 1) times its rest value; across
// a coordinate where it does not extend, it may shear by +-mu times the link's length. The bounds
// are on displacements (offset minus rest offset), so the rest shape may be curved (the
// diaphragm's dome). For a lattice with axis-aligned rest offsets these are Gibson's bounds; the
// seed's printed eqs. 3-8 abbreviate them (read literally, eqs. 5-6 give y_min = y_max for a link
// along x).
//
// Every bound is a difference constraint per coordinate (lo <= u_b - u_a <= hi with lo <= 0 <= hi),
// so a move is solved one coordinate at a time: drivers that went up raise their neighbours, in
// the order of their displacement (the largest first, as Gibson's sponsor lists), then drivers
// that went down lower theirs. Each element then sits at the nearest position its bounds allow:
// a move within the slack moves no neighbour, and a pulled chain's element k moves by
// max(0, D - k s (lambda - 1)).

#include <Eigen/Core>
#include <cstdint>
#include <span>
#include <vector>

namespace vesica::physics {

struct ChainMailParameters {
  double compression_gamma = 0.95;  ///< (0, 1]: a link's extent may shrink to gamma times rest
  double stretch_lambda = 1.05;     ///< >= 1: and grow to lambda times rest
  double shear_mu = 0.05;           ///< >= 0: sideways, +-mu times the link's length
};
void ValidateChainMailParameters(const ChainMailParameters& p, const char* organ);

class ChainMail {
 public:
  ChainMail(int element_count, const ChainMailParameters& parameters);

  /// Joins a to b, b resting at a + step_m. Throws std::invalid_argument for a == b or a zero step.
  void Link(int a, int b, const Eigen::Vector3d& step_m);
  /// A fixed element never moves; a move that would need it to is refused (MoveReport::blocked).
  void Fix(int element);
  [[nodiscard]] bool fixed(int element) const { return fixed_[static_cast<std::size_t>(element)] != 0; }

  struct MoveReport {
    int moved = 0;    ///< elements other than the drivers that moved
    int blocked = 0;  ///< times a fixed element (or a pinned driver) would have had to move
    [[nodiscard]] bool refused() const { return blocked > 0; }  ///< then u is left as it was
  };
  /// kPinned: each driver goes exactly to its target and stays there (the diaphragm's tendon, a
  /// needle's push). kAtLeast: a driver goes at least as far as its target along each coordinate
  /// and further where the mail carries it (the liver under its coupling forces: a target is where
  /// the element's coupling spring balances, the mail may not leave it behind).
  enum class Drivers { kPinned, kAtLeast };
  /// Moves each drivers[i] to displacement targets[i] and lets the mail follow. u: the current
  /// displacement of every element (in/out), which must satisfy the bounds on entry.
  /// also_pinned: elements held for this move only, as if fixed.
  MoveReport Move(std::span<const int> drivers, std::span<const Eigen::Vector3d> targets, std::span<Eigen::Vector3d> u,
                  Drivers mode = Drivers::kPinned, std::span<const int> also_pinned = {});

  /// The largest violation of any link's bounds by displacements u (0 when all hold), in metres.
  [[nodiscard]] double WorstViolation_m(std::span<const Eigen::Vector3d> u) const;

  /// Per coordinate, the least total slack from any of `from` to each element (how far `from`
  /// may move along +coordinate before the element must follow): a Dijkstra over the bounds.
  [[nodiscard]] std::vector<double> SlackFrom(std::span<const int> from, int coordinate, bool raise) const;

  [[nodiscard]] int element_count() const { return static_cast<int>(first_.size()) - 1; }
  [[nodiscard]] const ChainMailParameters& parameters() const { return parameters_; }
  [[nodiscard]] std::size_t link_count() const { return links_.size(); }

 private:
  struct Half {  // one direction of a link, stored with its element
    int other;
    float lo[3], hi[3];  // bounds on u_other - u_this
  };
  struct LinkRecord {
    int a, b;
    Eigen::Vector3d step_m;
  };
  void Finalise() const;  // builds the adjacency on first use after Link()
  struct Undo {
    int element, coordinate;
    double value;
  };
  int Pass(std::span<const int> seeds, int coordinate, bool raise, std::span<Eigen::Vector3d> u,
           std::span<const std::uint8_t> pinned, int& blocked) const;

  ChainMailParameters parameters_;
  std::vector<LinkRecord> links_;
  std::vector<std::uint8_t> fixed_;
  mutable std::vector<int> first_;  // CSR offsets into halves_
  mutable std::vector<Half> halves_;
  mutable bool dirty_ = true;
  mutable std::vector<std::uint8_t> pinned_scratch_;
  mutable std::vector<Undo> undo_;
  using Entry = std::pair<double, int>;
  mutable std::vector<Entry> heap_;
};

}  // namespace vesica::physics
