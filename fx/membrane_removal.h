#pragma once
// Connective-tissue membrane removal (paper §2.5.3): membrane elements touched by the active
// hook lose health (shown as opacity) at `fade_rate_per_s` and are removed at zero; a spring
// whose membrane elements are all removed is cut; the gallbladder is free when no spring
// remains. Generic over the membrane's geometry: element i only knows its springs.

#include <string>
#include <vector>

namespace vesica::fx {

struct MembraneParams {
  double fade_rate_per_s = 1.0;  ///< health lost per second of active contact, > 0 (health 1 -> 1/rate s)
};

struct ElementRemovedEvent {
  int element = -1;
  double time_s = 0;
};

struct SpringCutEvent {
  int spring = -1;
  double time_s = 0;
};

class MembraneRemoval {
 public:
  /// element_springs[i]: the springs membrane element i belongs to (indices in [0, num_springs)).
  /// Every spring must own at least one element. All elements start at health 1.
  MembraneRemoval(std::vector<std::vector<int>> element_springs, int num_springs, const MembraneParams& params);

  /// The active hook touches `element` for dt_s seconds; the step ends at time_s.
  /// Touching an element already removed does nothing.
  void Touch(int element, double dt_s, double time_s);

  int num_elements() const { return static_cast<int>(health_.size()); }
  int num_springs() const { return static_cast<int>(remaining_elements_.size()); }
  /// Per element in [0, 1]; the renderer uses it as opacity. 0 means removed.
  const std::vector<float>& health() const { return health_float_; }
  bool element_removed(int element) const;
  bool spring_cut(int spring) const;
  int num_springs_remaining() const { return springs_remaining_; }
  bool gallbladder_free() const { return springs_remaining_ == 0; }

  /// Everything removed so far, in order; physics drops springs from spring_cuts().
  const std::vector<ElementRemovedEvent>& element_removals() const { return element_removals_; }
  const std::vector<SpringCutEvent>& spring_cuts() const { return spring_cuts_; }

 private:
  MembraneParams params_;
  std::vector<std::vector<int>> element_springs_;
  std::vector<double> health_;
  std::vector<float> health_float_;
  std::vector<int> remaining_elements_;  ///< per spring, its elements not yet removed
  int springs_remaining_ = 0;
  std::vector<ElementRemovedEvent> element_removals_;
  std::vector<SpringCutEvent> spring_cuts_;
};

}  // namespace vesica::fx
