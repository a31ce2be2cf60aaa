#include "fx/membrane_removal.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "fx/input_checks.h"

namespace vesica::fx {

namespace {
const std::string kOwner = "MembraneRemoval";
}  // namespace

MembraneRemoval::MembraneRemoval(std::vector<std::vector<int>> element_springs, int num_springs,
                                 const MembraneParams& params)
    : params_(params), element_springs_(std::move(element_springs)) {
  CheckPositive(kOwner, "fade_rate_per_s", params.fade_rate_per_s);
  if (num_springs < 0) throw std::invalid_argument(kOwner + ": num_springs must be >= 0");
  remaining_elements_.assign(static_cast<size_t>(num_springs), 0);
  for (size_t i = 0; i < element_springs_.size(); ++i) {
    std::vector<int>& springs = element_springs_[i];
    std::sort(springs.begin(), springs.end());
    springs.erase(std::unique(springs.begin(), springs.end()), springs.end());
    for (int s : springs) {
      CheckIndex(kOwner + ": element " + std::to_string(i), "spring", s, num_springs);
      ++remaining_elements_[static_cast<size_t>(s)];
    }
  }
  for (int s = 0; s < num_springs; ++s) {
    if (remaining_elements_[static_cast<size_t>(s)] == 0) {
      throw std::invalid_argument(kOwner + ": spring " + std::to_string(s) +
                                  " has no membrane element, so it could never be cut");
    }
  }
  springs_remaining_ = num_springs;
  health_.assign(element_springs_.size(), 1.0);
  health_float_.assign(element_springs_.size(), 1.0f);
}

bool MembraneRemoval::element_removed(int element) const {
  CheckIndex(kOwner, "element", element, num_elements());
  return health_[static_cast<size_t>(element)] <= 0;
}

bool MembraneRemoval::spring_cut(int spring) const {
  CheckIndex(kOwner, "spring", spring, num_springs());
  return remaining_elements_[static_cast<size_t>(spring)] == 0;
}

void MembraneRemoval::Touch(int element, double dt_s, double time_s) {
  CheckIndex(kOwner, "element", element, num_elements());
  CheckNonNegative(kOwner, "dt_s", dt_s);
  if (!std::isfinite(time_s)) throw std::invalid_argument(kOwner + ": time_s is not finite");
  const auto e = static_cast<size_t>(element);
  if (health_[e] <= 0) return;
  health_[e] = std::max(0.0, health_[e] - params_.fade_rate_per_s * dt_s);
  health_float_[e] = static_cast<float>(health_[e]);
  if (health_[e] > 0) return;
  element_removals_.push_back({element, time_s});
  for (int s : element_springs_[e]) {
    if (--remaining_elements_[static_cast<size_t>(s)] == 0) {
      spring_cuts_.push_back({s, time_s});
      --springs_remaining_;
    }
  }
}

}  // namespace vesica::fx
