#include "app/history/plot_metrics.h"

#include <string>
#include <variant>

namespace vesica::app {

double PlotValue(const PlotMetric& metric, const SessionMetrics& metrics) {
  const double value = std::visit([&](auto member) { return static_cast<double>(metrics.*member); }, metric.member);
  return value * metric.scale;
}

int FindPlotMetric(std::string_view key) {
  for (std::size_t i = 0; i < kPlotMetrics.size(); ++i)
    if (key == kPlotMetrics[i].key) return static_cast<int>(i);
  return -1;
}

std::string AxisTitle(const PlotMetric& metric) {
  std::string title = metric.label;
  if (*metric.unit != '\0') title += std::string(" (") + metric.unit + ")";
  return title;
}

}  // namespace vesica::app
