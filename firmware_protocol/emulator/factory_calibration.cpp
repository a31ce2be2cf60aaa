#include "firmware_protocol/emulator/factory_calibration.h"

#include "firmware_protocol/emulator/arm_ground_truth.h"
#include "firmware_protocol/node/calibration_slot.h"

namespace vesica::fp::emulator {

ParameterStore FactoryCalibration(const ArmPlantParameters& plant, const Joint4& q0, const JointArray& park_position) {
  ArmGroundTruth truth;  // its per-joint views (friction at the joint, counts, index) of this plant
  truth.plant = plant;
  truth.power_up = q0;
  ParameterStore store;
  double node_over_true[3] = {};  // node torque units per true N m (N)
  for (int m = 0; m < 3; ++m) {
    const auto mm = static_cast<std::uint16_t>(m);
    const double node_nm_per_A = static_cast<double>(store.f32(param::kTorqueConstant + mm)) *
                                 static_cast<double>(store.f32(param::kGearRatio + mm));
    const double true_nm_per_A = plant.motor[m].torque_constant_Nm_per_A * plant.motor[m].transmission_ratio;
    node_over_true[m] = node_nm_per_A / true_nm_per_A;
    const int direction = plant.encoder[m].direction < 0 ? -1 : 1;
    // The node reads direction * (park + direction * counts * count) + offset; counts are whole
    // (floored), so half a count centres the reading on the truth.
    const double offset =
        q0[JointOfMotor(m)] - direction * static_cast<double>(park_position[m]) + 0.5 * truth.count(m);
    store.set_internal(param::kEncoderDirection + mm, static_cast<std::uint32_t>(direction));
    store.set_internal_f32(param::kPositionOffset + mm, static_cast<float>(offset));
    store.set_internal_f32(param::kCurrentOffset + mm, static_cast<float>(plant.current_sensor_offset_A[m]));
    store.set_internal_f32(param::kIndexPosition + mm, static_cast<float>(truth.reference_index(m)));
    store.set_internal_f32(param::kCoulombFriction + mm, static_cast<float>(truth.coulomb(m) * node_over_true[m]));
    store.set_internal_f32(param::kViscousFriction + mm, static_cast<float>(truth.viscous(m) * node_over_true[m]));
  }
  // The holding torque cancels gravity's.
  store.set_internal_f32(param::kGravitySin, static_cast<float>(-plant.pitch_gravity_sin_Nm * node_over_true[1]));
  store.set_internal_f32(param::kGravityCos, static_cast<float>(-plant.pitch_gravity_cos_Nm * node_over_true[1]));
  return store;
}

void ProgramFactoryFlash(EmulatedBoard& board, const ArmPlantParameters& plant, const Joint4& q0,
                         const JointArray& park_position, std::uint8_t node_id, std::uint32_t serial,
                         std::uint16_t layout) {
  SlotHeader header{1, 0, 0, serial};
  ParameterStore store;
  if (plant.factory_calibrated) {
    store = FactoryCalibration(plant, q0, park_position);
    header.date_s = kFactoryCalibrationDate_s;
    header.tool_version = kFactoryToolVersion;
  } else if (node_id == 1) {
    return;  // a blank board: the node boots on its defaults
  }
  store.write(param::kNodeId, ParameterType::U32, node_id);
  std::uint8_t image[ParameterStore::kImageSize];
  const std::size_t n = store.serialize(image, sizeof image, layout);
  std::uint8_t slot_image[slot::kSize];
  const std::size_t m = encode_slot(header, image, n, slot_image, sizeof slot_image);
  board.storage_write(slot::offset(0), slot_image, m);
}

}  // namespace vesica::fp::emulator
