#include "device/stylus/stylus_recorder.h"

#include <stdexcept>

namespace vesica::device {

void StylusRecorder::Append(double time_s, const StylusState& state) {
  StylusSample sample{time_s, state};
  const StylusSample* previous = recording_.samples.empty() ? nullptr : &recording_.samples.back();
  if (auto problem = StylusSampleProblem(sample, previous)) {
    throw std::invalid_argument("StylusRecorder: sample " + std::to_string(recording_.samples.size()) + ": " +
                                *problem);
  }
  sample.state = NormalizedStylus(sample.state);
  recording_.samples.push_back(sample);
}

}  // namespace vesica::device
