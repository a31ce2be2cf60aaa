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
