#pragma once

#include <cstdint>

#include "firmware_protocol/emulator/arm_plant_parameters.h"
#include "firmware_protocol/emulator/emulated_board.h"
#include "firmware_protocol/node/parameter_store.h"

namespace vesica::fp::emulator {

/// What the factory's calibration records in the slot header: a date (2026-01-01 00:00 UTC) and
/// a non-zero tool version, so the host reads the slot as a calibration, not as settings only.
inline constexpr std::uint32_t kFactoryCalibrationDate_s = 1'767'225'600;
inline constexpr std::uint32_t kFactoryToolVersion = 0x000100;  // 0.1.0, major << 16 | minor << 8 | patch

/// The parameters a perfect calibration of this arm would store, in the node's units: encoder
/// directions, position offsets (the board reads park_position + counts since power-up at q0),
/// current-sensor offsets, reference index, friction and the pitch's holding torque, the last
/// two scaled by the node's torque constant and gear ratio against the plant's. The soft joint
/// range stays the node's default (inside every nominal arm's hard stops).
/// q0: true joint positions at power-up (yaw, pitch, roll, insertion); park_position: where
/// the board assumes the arm powered up (yaw, pitch, insertion).
ParameterStore FactoryCalibration(const ArmPlantParameters& plant, const Joint4& q0, const JointArray& park_position);

/// Programs the board's flash as the factory leaves it, slot A generation 1: with
/// FactoryCalibration when plant.factory_calibrated, else (an arm nobody calibrated) only the
/// node id when it is not the default 1, else nothing (a blank board). layout: the image layout
/// (1 for firmware before protocol 1.3).
void ProgramFactoryFlash(EmulatedBoard& board, const ArmPlantParameters& plant, const Joint4& q0,
                         const JointArray& park_position, std::uint8_t node_id, std::uint32_t serial,
                         std::uint16_t layout = ParameterStore::kLayoutVersion);

}  // namespace vesica::fp::emulator
