// The calibration stored on a node, as the tool keeps a local copy of it: the slot image exactly
// as the node writes it to flash (header, parameter image, CRC-32; calibration_slot.h). Protocol
// 1.1 cannot send a slot's bytes, so the copy is rebuilt from the node's parameters (every
// persistent value read back) and the booted slot's header; `restore` writes such a copy back.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "device/calibration/calibration_link.h"
#include "device/calibration/node_info.h"
#include "firmware_protocol/node/calibration_slot.h"
#include "firmware_protocol/node/parameter_store.h"

namespace vesica::app::calibrate {

/// The calibration's values in a ParameterStore, joint order yaw, pitch, insertion.
struct CalibrationValues {
  struct Joint {
    int direction = 1;
    double position_offset = 0, current_offset_A = 0, joint_min = 0, joint_max = 0, index_position = 0;
    double coulomb = 0, viscous = 0;
    double torque_constant_correction = 1;  ///< layout 2 (protocol 1.3)
  };
  std::array<Joint, 3> joint;
  double gravity_sin = 0, gravity_cos = 0;
  /// Layout 2 (protocol 1.3): the hand sensors' calibration; closed = open, released = pressed:
  /// not measured.
  double roll_sensor_offset_rad = 0;
  std::uint32_t jaw_closed_counts = 0, jaw_open_counts = 0;
  std::uint32_t pedal_released_counts = 0, pedal_pressed_counts = 0;
};
CalibrationValues ValuesOf(const fp::ParameterStore& p);

struct StoredImage {
  fp::SlotHeader header;
  fp::ParameterStore params;
  std::uint16_t layout = fp::slot::kLayoutVersion;  ///< 1 for a node below protocol 1.3, or an old file
  std::vector<std::uint8_t> bytes;  ///< the slot's bytes (slot::size_of_layout(layout)), as in the node's flash
};

/// Reads the node's persistent parameters and builds the image of its booted slot (generation,
/// date and tool version from `info`). Throws CalibrationAbort as the link does.
StoredImage ReadStoredCalibration(device::calibration::CalibrationLink& link,
                                  const device::calibration::NodeInfo& info);
/// Encodes params + header into bytes.
void Encode(StoredImage& image);

/// Writes the image file; false with a message.
bool WriteImageFile(const std::string& path, const StoredImage& image, std::string* error);

/// What reading an image file found. exit_code: 0, kExitIo (unreadable) or kExitStorage (not a
/// calibration image, corrupt, another layout or parameter set).
struct ImageFileCheck {
  int exit_code = 0;
  std::string message;
  StoredImage image;
};
ImageFileCheck ReadImageFile(const std::string& path);

/// Writes the image's calibration back (every persistent read-write parameter but the node id,
/// its date and tool version) and saves: the node stores it in its older slot as the newest. A
/// node below protocol 1.3 gets layout 1's parameters only (it has no others).
void WriteToNode(device::calibration::CalibrationLink& link, const StoredImage& image);

/// "A" / "B" / "-".
std::string SlotName(int slot);

}  // namespace vesica::app::calibrate
