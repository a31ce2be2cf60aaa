#include "app/trainer/calibration_bus.h"

#include <stdexcept>

namespace vesica::app {

calibrate::BusSpec CalibrationBusOf(const Scenario& scenario, int arms_udp_base_port) {
  calibrate::BusSpec spec;
  spec.kind = calibrate::BusSpec::Kind::kUdp;
  spec.udp_host = "127.0.0.1";  // the bridge's emulated arms are on loopback
  spec.udp_base_port = arms_udp_base_port;
  for (const InstrumentConfig& c : scenario.instruments) {
    if (c.input != InputKind::kCanArm) continue;
    if (spec.kind == calibrate::BusSpec::Kind::kCan && spec.can_interface != c.can_interface)
      throw std::invalid_argument("the scenario's arms are on two CAN interfaces (" + spec.can_interface + " and " +
                                  c.can_interface + "); Tools > Calibrate arms opens one: calibrate with " +
                                  "vesica-calibrate --can IFACE");
    spec.kind = calibrate::BusSpec::Kind::kCan;
    spec.can_interface = c.can_interface;
  }
  return spec;
}

}  // namespace vesica::app
