#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "firmware_protocol/emulator/arm_plant.h"
#include "firmware_protocol/emulator/flash_model.h"
#include "firmware_protocol/node/node_hardware.h"

namespace vesica::fp::emulator {

/// The arm's controller board as the reference firmware node sees it (NodeHardware): encoder
/// counts turned into joint positions, a filtered velocity estimate, current sensors, the roll,
/// jaw, pedal and E-stop inputs, and the parameter flash (FlashModel: erase before write, power
/// can be cut at any byte).
///
/// Incremental encoders give positions relative to power-up; the board assumes the arm powers up
/// parked at `park_position` (yaw, pitch, insertion), so an arm that was not quite parked reads
/// off by the parking error until the node's FindIndex calibration runs.
class EmulatedBoard {
 public:
  struct Config {
    JointArray park_position{0.0f, 0.0f, 0.10f};  ///< rad, rad, m
    double velocity_filter_s = 1e-3;              ///< first-order filter on encoder differences
  };

  EmulatedBoard(ArmPlant& plant, const Config& config);

  // NodeHardware
  HardwareSample sense();
  void apply_currents(const JointArray& amps);
  bool storage_read(std::size_t offset, std::uint8_t* dst, std::size_t n);
  bool storage_write(std::size_t offset, const std::uint8_t* src, std::size_t n);

  /// Power on again (after ArmPlant::PowerUpAt): the velocity filter and the index edge count
  /// start afresh; the flash keeps what it holds.
  void PowerUp();

  void set_estop_input(bool open) { estop_open_ = open; }
  void set_handle_button(bool pressed) { handle_button_ = pressed; }
  /// The parameter flash (all 0xFF = blank board). Tests corrupt it or cut its power.
  FlashModel& flash() { return flash_; }
  const JointArray& applied_currents() const { return applied_; }

 private:
  JointArray EncoderPositions(const PlantSensors& s) const;

  ArmPlant& plant_;
  Config config_;
  JointArray applied_{};
  JointArray last_position_{};
  JointArray velocity_{};
  std::array<std::uint32_t, 3> last_index_edges_{};
  double last_sense_s_ = 0.0;
  bool estop_open_ = false;
  bool handle_button_ = false;
  FlashModel flash_;
};

static_assert(NodeHardware<EmulatedBoard>);

}  // namespace vesica::fp::emulator
