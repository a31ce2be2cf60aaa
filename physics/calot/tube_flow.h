#pragma once
// Where bile or blood is along one tube, from its clips and cuts alone: fluid fills what an
// open path joins to a pressurised end (the liver's bile, the gallbladder's bile, the hepatic
// artery's blood); a clip occludes, a cut opens two ends. A leak is an open end that fluid
// reaches (docs/calot.md).

#include <vector>

namespace vesica::physics::calot {

struct TubeFlowState {
  double length_m = 0.0;          ///< material coordinates run 0..length_m, > 0
  bool start_pressurised = true;  ///< fluid under pressure behind s = 0
  bool end_pressurised = true;    ///< behind s = length_m
  std::vector<double> clips_s_m;  ///< clips, any order, m
  std::vector<double> cuts_s_m;   ///< cuts, any order, m
};

/// Fluid is at s: no clip or cut lies strictly between s and a pressurised end.
bool FluidAt(const TubeFlowState& tube, double s_m);
/// Fluid flows through s: s is joined to both ends without a clip or cut between, and one of
/// them is pressurised. A clip anywhere stops the flow along the whole tube.
bool FlowPasses(const TubeFlowState& tube, double s_m);

struct OpenEndLeak {
  double s_m = 0.0;          ///< the cut's material coordinate
  bool patient_side = true;  ///< the stump that runs toward s = 0 (the hilum, junction or hepatic artery)
};
/// Each cut's two open ends that fluid reaches (a stump closed by a clip, or a piece between two
/// cuts, stays dry), in order of s, the patient's side first.
std::vector<OpenEndLeak> LeakingEnds(const TubeFlowState& tube);

}  // namespace vesica::physics::calot
