#include "firmware_protocol/emulator/emulated_board.h"

#include <cmath>
#include <numbers>

namespace vesica::fp::emulator {

EmulatedBoard::EmulatedBoard(ArmPlant& plant, const Config& config) : plant_(plant), config_(config) {
  const PlantSensors s = plant_.ReadSensors();
  last_position_ = EncoderPositions(s);
  last_index_edges_ = s.index_edges;
  last_sense_s_ = plant_.time_s();
}

void EmulatedBoard::PowerUp() {
  const PlantSensors s = plant_.ReadSensors();
  applied_ = JointArray{};
  velocity_ = JointArray{};
  last_position_ = EncoderPositions(s);
  last_index_edges_ = s.index_edges;
  last_sense_s_ = plant_.time_s();
}

JointArray EmulatedBoard::EncoderPositions(const PlantSensors& s) const {
  const ArmPlantParameters& p = plant_.parameters();
  JointArray out{};
  for (int m = 0; m < kJointCount; ++m) {
    const double joint_per_count =
        2.0 * std::numbers::pi / p.encoder[m].counts_per_rev / p.motor[m].transmission_ratio;
    const int direction = p.encoder[m].direction < 0 ? -1 : 1;
    out[m] = static_cast<float>(config_.park_position[m] + direction * s.encoder_count[m] * joint_per_count);
  }
  return out;
}

HardwareSample EmulatedBoard::sense() {
  const PlantSensors s = plant_.ReadSensors();
  HardwareSample h;
  h.position = EncoderPositions(s);
  const double dt = plant_.time_s() - last_sense_s_;
  if (dt > 0.0) {
    const double alpha = 1.0 - std::exp(-dt / config_.velocity_filter_s);
    for (int m = 0; m < kJointCount; ++m) {
      const double raw = (h.position[m] - last_position_[m]) / dt;
      velocity_[m] = static_cast<float>(velocity_[m] + alpha * (raw - velocity_[m]));
    }
  }
  last_position_ = h.position;
  last_sense_s_ = plant_.time_s();
  h.velocity = velocity_;
  for (int m = 0; m < kJointCount; ++m) {
    h.current[m] = static_cast<float>(s.current_A[m]);
    h.index_seen[m] = s.index_edges[m] != last_index_edges_[m];
  }
  last_index_edges_ = s.index_edges;
  h.roll_rad = static_cast<float>(s.roll_rad);
  h.jaw_rad = static_cast<float>(s.jaw_rad);
  h.pedal = s.pedal;
  h.roll_raw = s.roll_raw;
  h.jaw_raw = s.jaw_raw;
  h.pedal_raw = s.pedal_raw;
  h.handle_button = handle_button_;
  h.estop_input = estop_open_;
  h.bus_V = static_cast<float>(s.bus_V);
  h.board_temperature_degC = static_cast<float>(s.board_temperature_degC);
  return h;
}

void EmulatedBoard::apply_currents(const JointArray& amps) {
  applied_ = amps;
  plant_.SetCurrentSetpoints({amps[0], amps[1], amps[2]});
}

bool EmulatedBoard::storage_read(std::size_t offset, std::uint8_t* dst, std::size_t n) {
  return flash_.Read(offset, dst, n);
}

bool EmulatedBoard::storage_write(std::size_t offset, const std::uint8_t* src, std::size_t n) {
  return flash_.Write(offset, src, n);
}

}  // namespace vesica::fp::emulator
