#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "firmware_protocol/transport/transport.h"

namespace vesica::app {

/// Where vesica-armsim listens and whom it talks to (CAN over UDP, cannelloni format).
struct ArmsimUdpOptions {
  int local_port = 20000;
  std::string remote_host = "127.0.0.1";
  int remote_port = 20001;
};

/// Opens the UDP transport; false with a message naming the port or address on failure.
bool OpenArmsimUdp(const ArmsimUdpOptions& options, std::unique_ptr<fp::Transport>* out, std::string* error);

}  // namespace vesica::app
