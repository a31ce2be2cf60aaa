#pragma once

#include <string_view>

namespace vesica::device {

/// Why a device call did not do what was asked. Every value has a name for logs and UIs.
enum class DeviceStatus {
  kOk,
  kNotOpen,          ///< call needs open() first
  kAlreadyOpen,
  kConnecting,       ///< handshake with the node under way (version, start, enable)
  kNoResponse,       ///< open(): the node never answered within the timeout
  kLinkLost,         ///< no joint state for longer than the loss timeout; commands stopped
  kNodeFault,        ///< the node latched a fault (watchdog, limit, E-stop); needs ResetFault()
  kNotCalibrated,    ///< the node has no valid calibration in force: never enabled (run vesica-calibrate)
  kTransportError,   ///< the transport refused to send or reported a bus error
  kInvalidArgument,  ///< non-finite force, unknown joint, bad configuration
};

constexpr std::string_view ToString(DeviceStatus s) {
  switch (s) {
    case DeviceStatus::kOk: return "ok";
    case DeviceStatus::kNotOpen: return "not open";
    case DeviceStatus::kAlreadyOpen: return "already open";
    case DeviceStatus::kConnecting: return "connecting";
    case DeviceStatus::kNoResponse: return "no response from node";
    case DeviceStatus::kLinkLost: return "link lost";
    case DeviceStatus::kNodeFault: return "node fault";
    case DeviceStatus::kNotCalibrated: return "no valid calibration";
    case DeviceStatus::kTransportError: return "transport error";
    case DeviceStatus::kInvalidArgument: return "invalid argument";
  }
  return "unknown";
}

}  // namespace vesica::device
