#pragma once
// Tick positions for a plot axis: "nice" steps (1, 2 or 5 times a power of ten) that cover a
// data range with a handful of labelled ticks. Qt-free.

#include <string>
#include <vector>

namespace vesica::app {

struct AxisTicks {
  double step = 1;             // distance between ticks, > 0
  std::vector<double> values;  // ascending; front() <= data minimum, back() >= data maximum
  int decimals = 0;            // decimals that tell the tick labels apart
};

/// Ticks covering [lo, hi] with a nice step no smaller than (hi - lo) / (max_ticks - 1), so at
/// most max_ticks + 1 ticks. hi <= lo (one value, or no spread) covers [lo, lo + 1] instead;
/// max_ticks < 2 counts as 2; non-finite input gives the ticks of [0, 1].
/// Example: NiceTicks(0, 7.3, 6) = {0, 2, 4, 6, 8}, step 2.
AxisTicks NiceTicks(double lo, double hi, int max_ticks);

/// Session-number ticks for sessions 1..count: every number when count <= max_ticks, otherwise
/// 1 and the multiples of a nice integer step (count 23, max 6 -> {1, 5, 10, 15, 20}).
/// Empty for count <= 0.
std::vector<int> SessionNumberTicks(int count, int max_ticks);

/// A tick label with `decimals` decimals, "-0" printed as "0".
std::string TickLabel(double value, int decimals);

}  // namespace vesica::app
