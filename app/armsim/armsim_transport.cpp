#include "app/armsim/armsim_transport.h"

#include "firmware_protocol/transport/udp_transport.h"

namespace vesica::app {

bool OpenArmsimUdp(const ArmsimUdpOptions& options, std::unique_ptr<fp::Transport>* out, std::string* error) {
  if (options.local_port < 1 || options.local_port > 65535 || options.remote_port < 1 || options.remote_port > 65535) {
    *error = "UDP ports must be 1..65535";
    return false;
  }
  fp::UdpTransportConfig config;
  config.local_port = static_cast<std::uint16_t>(options.local_port);
  config.remote_address = options.remote_host;
  config.remote_port = static_cast<std::uint16_t>(options.remote_port);
  std::string why;
  std::unique_ptr<fp::UdpTransport> t = fp::UdpTransport::open(config, why);
  if (!t) {
    *error = "cannot open UDP port " + std::to_string(options.local_port) + " toward " + options.remote_host + ":" +
             std::to_string(options.remote_port) + ": " + why;
    return false;
  }
  *out = std::move(t);
  return true;
}

}  // namespace vesica::app
