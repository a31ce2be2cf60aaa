// restore: the node's other slot (through the image archive) or a file puts an earlier
// calibration back in force as the newest slot; verify passes on an unchanged arm.
#include <gtest/gtest.h>

#include <fstream>

#include "app/calibrate/exit_codes.h"
#include "firmware_protocol/node/calibration_slot.h"
#include "tool_process.h"

namespace vesica::app::calibrate {
namespace {

using testing::RunTool;

TEST(CalibrateRestore, TheOtherSlotAndAFileComeBackAsTheNewestCalibration) {
  const std::string dir = testing::FreshDir("restore");
  const std::vector<std::string> bus = {"--emulated", "21", "--dir", dir, "--yes", "--quiet", "--json"};
  auto with = [&](std::vector<std::string> more) {
    std::vector<std::string> all = bus;
    all.insert(all.end(), more.begin(), more.end());
    return RunTool(all);
  };
  // Two calibrations: generation 1 (slot A, date 1) then friction of pitch again (slot B, date 2).
  auto first = with({"--date", "1790000000", "calibrate", "1"});
  ASSERT_EQ(first.exit_code, 0) << first.err;
  auto second = with({"--date", "1790086400", "calibrate", "1", "--step", "friction", "--joint", "pitch"});
  ASSERT_EQ(second.exit_code, 0) << second.err;
  EXPECT_EQ(second.json()["node_after"]["active_slot"], "B");
  EXPECT_EQ(second.json()["steps"].size(), 1u);
  // Friction alone of pitch: everything else as it was.
  EXPECT_EQ(second.json()["after"]["yaw"], first.json()["after"]["yaw"]);
  EXPECT_EQ(second.json()["after"]["pitch"]["joint_min"], first.json()["after"]["pitch"]["joint_min"]);

  // restore with no option: the slot not in use (A, generation 1), stored again as generation 3.
  auto back = with({"restore", "1"});
  ASSERT_EQ(back.exit_code, 0) << back.err;
  const nlohmann::json b = back.json();
  EXPECT_EQ(b["restored_generation"], 1);
  EXPECT_EQ(b["node_after"]["active_slot"], "A");
  EXPECT_EQ(b["node_after"]["slots"][0]["generation"], 3);
  EXPECT_EQ(b["node_after"]["calibration_date_s"], 1790000000);
  EXPECT_EQ(b["after"], first.json()["after"]);
  EXPECT_EQ(b["before"], second.json()["after"]);

  // restore --slot of the slot in use: nothing to do.
  auto same = with({"restore", "1", "--slot", "A"});
  EXPECT_EQ(same.exit_code, kExitUsage);
  EXPECT_EQ(same.json()["error"]["message"], "arm 1: slot A is already in force; nothing to do");

  // From the file beside the second calibration's report: its values again, generation 4.
  const std::string file = second.json()["session_dir"].get<std::string>() + "/arm1-stored.vcal";
  auto from_file = with({"restore", "1", "--file", file});
  ASSERT_EQ(from_file.exit_code, 0) << from_file.err;
  EXPECT_EQ(from_file.json()["after"], second.json()["after"]);
  EXPECT_EQ(from_file.json()["node_after"]["slots"][1]["generation"], 4);

  // The arm still is what its calibration says: verify passes and writes nothing to it.
  auto verify = with({"verify", "1"});
  ASSERT_EQ(verify.exit_code, 0) << verify.err;
  EXPECT_TRUE(verify.json()["all_pass"].get<bool>());
  EXPECT_FALSE(verify.json()["saved"].get<bool>());
  EXPECT_EQ(verify.json()["after"], nullptr);

  // report: the calibration in force, with its image copy; --log puts the bus log where asked.
  const std::string log = dir + "-report.log";
  auto report = with({"--log", log, "report", "1"});
  EXPECT_EQ(report.json()["bus_log"], log);
  EXPECT_TRUE(std::filesystem::exists(log));
  ASSERT_EQ(report.exit_code, 0) << report.err;
  EXPECT_EQ(report.json()["before"], second.json()["after"]);
  EXPECT_EQ(report.json()["files"]["image_stored"], "arm1-stored.vcal");

  // The image of another arm (serial) is refused.
  auto other = RunTool({"--emulated", "21", "--dir", dir, "--json", "restore", "2", "--file", file});
  EXPECT_EQ(other.exit_code, kExitStorage);
  EXPECT_EQ(other.json()["error"]["message"], "arm 2: " + file +
                                                  " is the calibration of serial 0x5E51CA01, this arm is serial "
                                                  "0x5E51CA02; nothing was written");
}

// An image file of a 1.0 .. 1.2 tool (image layout 1) restores onto a 1.3 node: its values come
// back, stored as layout 2, the values layout 1 lacks neutral.
TEST(CalibrateRestore, AnImageFileOfImageLayout1IsRestoredAsLayout2) {
  const std::string dir = testing::FreshDir("restore-layout1");
  const std::vector<std::string> bus = {"--emulated", "21", "--dir", dir, "--yes", "--quiet", "--json"};
  auto with = [&](std::vector<std::string> more) {
    std::vector<std::string> all = bus;
    all.insert(all.end(), more.begin(), more.end());
    return RunTool(all);
  };
  auto first = with({"--date", "1790000000", "calibrate", "1"});
  ASSERT_EQ(first.exit_code, 0) << first.err;
  // The stored image, written again as a 1.2 tool kept it.
  const auto bytes = testing::ReadBytes(first.json()["session_dir"].get<std::string>() + "/arm1-stored.vcal");
  const fp::SlotCheck check = fp::check_slot(bytes.data(), bytes.size());
  ASSERT_EQ(check.status, fp::StorageResult::Ok);
  ASSERT_EQ(check.layout, 2);
  fp::ParameterStore params;
  ASSERT_EQ(params.deserialize(bytes.data() + fp::slot::kHeaderSize, bytes.size() - fp::slot::kHeaderSize - 4),
            fp::StorageResult::Ok);
  std::uint8_t image[fp::ParameterStore::kImageSize];
  const std::size_t n = params.serialize(image, sizeof image, 1);
  std::uint8_t slot[fp::slot::kSize];
  ASSERT_EQ(fp::encode_slot(check.header, image, n, slot, sizeof slot), fp::slot::kLayout1Size);
  const std::string old = dir + "-layout1.vcal";
  std::ofstream(old, std::ios::binary).write(reinterpret_cast<const char*>(slot), fp::slot::kLayout1Size);

  // A second calibration, so that the restore has something to replace.
  ASSERT_EQ(with({"--date", "1790086400", "calibrate", "1", "--step", "friction"}).exit_code, 0);
  auto back = with({"restore", "1", "--file", old});
  ASSERT_EQ(back.exit_code, 0) << back.err;
  EXPECT_EQ(back.json()["after"], first.json()["after"]);
  auto info = with({"info", "1"});
  ASSERT_EQ(info.exit_code, 0) << info.err;
  EXPECT_EQ(info.json()["node"]["image_layout"], 2);
  EXPECT_EQ(info.json()["node"]["calibration_date_s"], 1790000000);
}

}  // namespace
}  // namespace vesica::app::calibrate
