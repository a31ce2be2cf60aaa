#include "physics/calot/tube_flow.h"

#include <algorithm>

namespace vesica::physics::calot {
namespace {

bool BarrierBelow(const TubeFlowState& tube, double s) {
  auto below = [s](double b) { return b < s; };
  return std::any_of(tube.clips_s_m.begin(), tube.clips_s_m.end(), below) ||
         std::any_of(tube.cuts_s_m.begin(), tube.cuts_s_m.end(), below);
}

bool BarrierAbove(const TubeFlowState& tube, double s) {
  auto above = [s](double b) { return b > s; };
  return std::any_of(tube.clips_s_m.begin(), tube.clips_s_m.end(), above) ||
         std::any_of(tube.cuts_s_m.begin(), tube.cuts_s_m.end(), above);
}

}  // namespace

bool FluidAt(const TubeFlowState& tube, double s_m) {
  return (tube.start_pressurised && !BarrierBelow(tube, s_m)) || (tube.end_pressurised && !BarrierAbove(tube, s_m));
}

bool FlowPasses(const TubeFlowState& tube, double s_m) {
  return (tube.start_pressurised || tube.end_pressurised) && !BarrierBelow(tube, s_m) && !BarrierAbove(tube, s_m);
}

std::vector<OpenEndLeak> LeakingEnds(const TubeFlowState& tube) {
  std::vector<double> cuts = tube.cuts_s_m;
  std::sort(cuts.begin(), cuts.end());
  std::vector<OpenEndLeak> leaks;
  for (double cut : cuts) {
    // The patient-side stump reaches back toward s = 0 only; the other toward the end only.
    if (tube.start_pressurised && !BarrierBelow(tube, cut)) leaks.push_back({cut, true});
    if (tube.end_pressurised && !BarrierAbove(tube, cut)) leaks.push_back({cut, false});
  }
  return leaks;
}

}  // namespace vesica::physics::calot
