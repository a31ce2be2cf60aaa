// What `info` reads from an arm: a corrupt slot is named while the arm runs on the other one; with
// both gone the latched parameter_crc fault and the defaults are said.
#include "device/calibration/node_info.h"

#include <gtest/gtest.h>

#include "calibration_rig.h"
#include "firmware_protocol/node/parameter_table.h"

namespace vesica::device::calibration {
namespace {

using testing::CalibrationRig;

void SaveTwice(CalibrationLink& link) {
  link.Connect();
  link.WriteU32(fp::param::kCalibrationDate_s, 1'767'225'600u);  // 2026-01-01 00:00 UTC
  link.WriteU32(fp::param::kCalibrationToolVersion, 0x010203);
  link.Save();  // A, generation 1
  link.Save();  // B, generation 2
}

// Slot A as a 1.2 tool wrote it: image layout 1 (the table's first 70 parameters).
void WriteLayout1SlotA(CalibrationRig& rig) {
  fp::ParameterStore store;
  store.set_internal_f32(fp::param::kPositionOffset, 0.25f);
  std::uint8_t image[fp::ParameterStore::kImageSize];
  const std::size_t n = store.serialize(image, sizeof image, 1);
  ASSERT_EQ(n, fp::ParameterStore::kLayout1ImageSize);
  std::uint8_t slot[fp::slot::kSize];
  ASSERT_EQ(fp::encode_slot(fp::SlotHeader{1, 1'767'225'600u, 0x000100, 0x5E51CA01u}, image, n, slot, sizeof slot),
            fp::slot::kLayout1Size);
  rig.emulator->board().storage_write(fp::slot::offset(0), slot, fp::slot::kLayout1Size);
}

TEST(NodeInfoTest, ALayout1ImageIsSaidAndWhatItLacksListed) {
  CalibrationRig rig(1);
  WriteLayout1SlotA(rig);
  rig.emulator->Reboot();
  const NodeInfo info = ReadNodeInfo(*rig.link);
  EXPECT_EQ(info.active_slot, 0);
  EXPECT_EQ(info.stored_layout, 1);
  const std::vector<std::string> absent = info.AbsentFields();
  const std::vector<std::string> expected{"torque_constant_correction[yaw]",
                                          "torque_constant_correction[pitch]",
                                          "torque_constant_correction[insertion]",
                                          "roll_sensor_offset",
                                          "jaw_closed_counts",
                                          "jaw_open_counts",
                                          "jaw_open_rad",
                                          "pedal_released_counts",
                                          "pedal_pressed_counts"};
  EXPECT_EQ(absent, expected);
  const std::string text = info.Describe();
  EXPECT_NE(text.find("tool 0.1.0, image layout 1\n  layout 1 (a 1.0 .. 1.2 tool's) lacks, neutral: "
                      "torque_constant_correction[yaw]"),
            std::string::npos)
      << text;
  EXPECT_FLOAT_EQ(rig.emulator->node().parameters().f32(fp::param::kPositionOffset), 0.25f);
}

TEST(NodeInfoTest, ANodeOfProtocol1Point2KeepsLayout1OnlyAndSaysSo) {
  CalibrationRig rig(1);
  WriteLayout1SlotA(rig);
  rig.emulator->node().emulate_firmware_minor(2);
  rig.emulator->Reboot();
  const NodeInfo info = ReadNodeInfo(*rig.link);  // reads no layout-2 parameter: the node has none
  EXPECT_EQ(info.identity.max_minor, 2);
  EXPECT_EQ(info.stored_layout, 1);
  EXPECT_NE(info.Describe().find("this node (protocol 1.2) keeps layout 1 only; it has no: "
                                 "torque_constant_correction[yaw]"),
            std::string::npos)
      << info.Describe();
}

TEST(NodeInfoTest, ACorruptSlotIsNamedWhileTheOtherIsInUse) {
  CalibrationRig rig(1);
  SaveTwice(*rig.link);
  rig.emulator->board().flash().bytes()[fp::slot::offset(1) + 100] ^= 0x10;
  rig.emulator->Reboot();
  const NodeInfo info = ReadNodeInfo(*rig.link);
  EXPECT_EQ(info.active_slot, 0);
  EXPECT_EQ(info.slot_status[1], fp::StorageResult::BadCrc);
  EXPECT_EQ(info.slot_generation[0], 1u);
  EXPECT_EQ(info.latched_fault, fp::FaultCode::None);
  EXPECT_EQ(info.identity.serial, 0x5E51CA01u);
  const std::string text = info.Describe();
  EXPECT_NE(text.find("slot A: ok, generation 1 (in use)"), std::string::npos) << text;
  EXPECT_NE(text.find("slot B: corrupt (bad CRC)"), std::string::npos) << text;
  EXPECT_NE(text.find("calibration: slot A, generation 1, 2026-01-01 00:00 UTC, tool 1.2.3"), std::string::npos)
      << text;
}

TEST(NodeInfoTest, BothSlotsCorruptShowsTheFaultAndNoCalibration) {
  CalibrationRig rig(2);
  SaveTwice(*rig.link);
  rig.emulator->board().flash().bytes()[fp::slot::offset(0) + 30] ^= 0x01;
  rig.emulator->board().flash().bytes()[fp::slot::offset(1) + 30] ^= 0x01;
  rig.emulator->Reboot();
  const NodeInfo info = ReadNodeInfo(*rig.link);
  EXPECT_EQ(info.active_slot, -1);
  EXPECT_EQ(info.latched_fault, fp::FaultCode::ParameterCrc);
  ASSERT_FALSE(info.fault_history.empty());
  EXPECT_EQ(info.fault_history.front(), fp::FaultCode::ParameterCrc);
  const std::string text = info.Describe();
  EXPECT_NE(text.find("fault: parameter_crc"), std::string::npos) << text;
  EXPECT_NE(text.find("calibration: none in force (defaults)"), std::string::npos) << text;
  EXPECT_NE(text.find("slot A: corrupt (bad CRC)"), std::string::npos) << text;
}

}  // namespace
}  // namespace vesica::device::calibration
