#pragma once
// Where Tools > Calibrate arms finds the arms: on the transport the trainer drives them with
// (app/session/arm_bridge.h), in the calibration tool's terms (app/calibrate/tool_bus.h). A
// scenario whose arm instruments are `can_arm` gives their SocketCAN interface; otherwise the
// emulated arms, vesica-armsim over UDP on loopback from the trainer's --arms-udp-base-port.

#include "app/calibrate/tool_bus.h"
#include "app/scenario/scenario.h"

namespace vesica::app {

/// Throws std::invalid_argument when the scenario's arms are on two different CAN interfaces
/// (the tool opens one bus), naming both.
calibrate::BusSpec CalibrationBusOf(const Scenario& scenario, int arms_udp_base_port);

}  // namespace vesica::app
