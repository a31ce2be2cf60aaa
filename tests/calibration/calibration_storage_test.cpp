// The node's two calibration slots on a flash that loses power: a save cut at every byte offset,
// into either slot, never leaves the arm without a valid calibration, and the node boots the
// previous one; a corrupt slot is named over the protocol. Image layout 2 (protocol 1.3) is what
// a save writes; a layout-1 slot written by a 1.2 tool still boots, migrated.
#include <gtest/gtest.h>

#include <algorithm>
#include <iterator>
#include <vector>

#include "firmware_protocol/emulator/flash_model.h"
#include "firmware_protocol/node/node.h"

namespace vesica::fp {
namespace {

using emulator::FlashModel;

// A board that is only its parameter flash.
struct FlashBoard {
  FlashModel flash{2 * slot::kStride, 256};
  HardwareSample sense() { return {}; }
  void apply_currents(const JointArray&) {}
  bool storage_read(std::size_t offset, std::uint8_t* dst, std::size_t n) { return flash.Read(offset, dst, n); }
  bool storage_write(std::size_t offset, const std::uint8_t* src, std::size_t n) { return flash.Write(offset, src, n); }
};
static_assert(NodeHardware<FlashBoard>);

constexpr std::uint32_t kSerial = 0x5E51CA01;

ParameterResponse Ask(Node<FlashBoard>& node, const ParameterRequest& r) {
  CanFrame f;
  EXPECT_EQ(encode(r, f), EncodeError::None);
  CanFrame out;
  while (node.pop_tx(out)) {
  }
  node.on_frame(f, 0);
  while (node.pop_tx(out)) {
    Message m;
    if (decode(out, m) == DecodeError::None)
      if (const auto* p = std::get_if<ParameterResponse>(&m)) return *p;
  }
  ADD_FAILURE() << "no parameter response";
  return {};
}
std::uint32_t ReadU32(Node<FlashBoard>& node, std::uint16_t index) {
  return Ask(node, ParameterRequest{1, ParameterOp::Read, ParameterType::None, index, 0}).raw_value;
}
// The layout-2 value a calibration with this offset stores (SaveCalibration).
float CorrectionFor(float offset) { return 1.0f + offset / 10; }

// One calibration: a position offset, a friction value, a torque-constant correction and a jaw
// span (layout 2) and the date that identify it.
bool SaveCalibration(Node<FlashBoard>& node, float offset, std::uint32_t date_s) {
  EXPECT_FALSE(Ask(node, {1, ParameterOp::Write, ParameterType::F32, param::kTorqueConstantCorrection + 2,
                          f32_bits(CorrectionFor(offset))})
                   .aborted);
  EXPECT_FALSE(Ask(node, {1, ParameterOp::Write, ParameterType::U32, param::kJawOpenCounts, date_s / 10}).aborted);
  EXPECT_FALSE(
      Ask(node, {1, ParameterOp::Write, ParameterType::F32, param::kPositionOffset, f32_bits(offset)}).aborted);
  EXPECT_FALSE(
      Ask(node, {1, ParameterOp::Write, ParameterType::F32, param::kCoulombFriction + 1, f32_bits(offset / 10)})
          .aborted);
  EXPECT_FALSE(Ask(node, {1, ParameterOp::Write, ParameterType::U32, param::kCalibrationDate_s, date_s}).aborted);
  EXPECT_FALSE(
      Ask(node, {1, ParameterOp::Write, ParameterType::U32, param::kCalibrationToolVersion, 0x010200}).aborted);
  return !Ask(node, {1, ParameterOp::Save, ParameterType::None, 0, 0}).aborted;
}

struct Booted {
  FlashBoard board;
  Node<FlashBoard> node{board, kSerial};
  explicit Booted(const std::vector<std::uint8_t>& flash) {
    board.flash.bytes() = flash;
    node.boot(0);
  }
};

TEST(CalibrationStorageTest, SavesAlternateBetweenSlotsWithRisingGenerations) {
  FlashBoard board;
  Node<FlashBoard> node(board, kSerial);
  node.boot(0);
  EXPECT_EQ(node.active_slot(), -1);
  EXPECT_EQ(node.latched_fault(), FaultCode::None);  // blank: a new board
  EXPECT_EQ(ReadU32(node, param::kActiveSlot), 255u);
  ASSERT_TRUE(SaveCalibration(node, 0.1f, 1000));
  EXPECT_EQ(node.active_slot(), 0);
  ASSERT_TRUE(SaveCalibration(node, 0.2f, 2000));
  EXPECT_EQ(node.active_slot(), 1);
  ASSERT_TRUE(SaveCalibration(node, 0.3f, 3000));
  EXPECT_EQ(node.active_slot(), 0);  // the older slot is the one overwritten
  Booted again(board.flash.bytes());
  EXPECT_EQ(again.node.active_slot(), 0);
  EXPECT_EQ(again.node.slot_generation(0), 3u);
  EXPECT_EQ(again.node.slot_generation(1), 2u);
  EXPECT_FLOAT_EQ(again.node.parameters().f32(param::kPositionOffset), 0.3f);
  EXPECT_EQ(ReadU32(again.node, param::kCalibrationDate_s), 3000u);
  EXPECT_EQ(ReadU32(again.node, param::kCalibrationToolVersion), 0x010200u);
  EXPECT_EQ(ReadU32(again.node, param::kSlotGeneration + 0), 3u);
  EXPECT_EQ(ReadU32(again.node, param::kSlotStatus + 1), static_cast<std::uint32_t>(StorageResult::Ok));
}

// Power cut after k byte operations of a save, for every k: erase and program of the target.
// previous_correction: the torque-constant correction in force before (1 from a layout-1 slot).
void CutEverywhere(const std::vector<std::uint8_t>& before, float previous_offset, float previous_correction,
                   int previous_slot, int target) {
  const std::size_t operations = FlashModel(2 * slot::kStride, 256).OperationsFor(slot::offset(target), slot::kSize);
  ASSERT_GT(operations, slot::kSize);
  std::size_t previous_kept = 0, complete_before_the_end = 0;
  for (std::size_t k = 0; k <= operations; ++k) {
    Booted b(before);
    ASSERT_EQ(b.node.active_slot(), previous_slot);
    b.board.flash.CutPowerAfter(k);
    const bool saved = SaveCalibration(b.node, 0.9f, 9000);
    b.board.flash.RestorePower();
    Booted after(b.board.flash.bytes());  // power back: the node boots again
    ASSERT_EQ(after.node.latched_fault(), FaultCode::None) << "cut after " << k;
    if (k < operations) {
      EXPECT_FALSE(saved) << k;
      if (after.node.active_slot() == target) {
        // Cut in the last byte, whose half-programmed bits happened to be all it needed: the new
        // slot is complete and valid (it has the next generation), so it is the one booted.
        ++complete_before_the_end;
        ASSERT_EQ(k, operations - 1);
        ASSERT_FLOAT_EQ(after.node.parameters().f32(param::kPositionOffset), 0.9f);
        ASSERT_EQ(after.node.slot_generation(target), after.node.slot_generation(previous_slot) + 1);
      } else {
        ASSERT_EQ(after.node.active_slot(), previous_slot) << "cut after " << k << " of " << operations;
        ASSERT_FLOAT_EQ(after.node.parameters().f32(param::kPositionOffset), previous_offset) << k;
        ASSERT_FLOAT_EQ(after.node.parameters().f32(param::kTorqueConstantCorrection + 2), previous_correction) << k;
        ASSERT_NE(after.node.slot_status(target), StorageResult::Ok) << k;
        ++previous_kept;
      }
    } else {
      EXPECT_TRUE(saved);  // the whole write went through: the new calibration is in force
      EXPECT_EQ(after.node.active_slot(), target);
      EXPECT_EQ(after.node.stored_layout(), 2);
      EXPECT_FLOAT_EQ(after.node.parameters().f32(param::kPositionOffset), 0.9f);
      EXPECT_FLOAT_EQ(after.node.parameters().f32(param::kTorqueConstantCorrection + 2), CorrectionFor(0.9f));
      EXPECT_EQ(after.node.parameters().u32(param::kJawOpenCounts), 900u);
    }
    ASSERT_EQ(after.node.slot_status(previous_slot), StorageResult::Ok) << k;
  }
  EXPECT_GE(previous_kept, operations - 1);
  EXPECT_EQ(previous_kept + complete_before_the_end, operations);
}

TEST(CalibrationStorageTest, PowerCutAtEveryByteOfASaveIntoSlotBKeepsSlotA) {
  FlashBoard board;
  Node<FlashBoard> node(board, kSerial);
  node.boot(0);
  ASSERT_TRUE(SaveCalibration(node, 0.1f, 1000));  // A, generation 1; B blank
  CutEverywhere(board.flash.bytes(), 0.1f, CorrectionFor(0.1f), 0, 1);
}

TEST(CalibrationStorageTest, PowerCutAtEveryByteOfASaveIntoSlotAKeepsSlotB) {
  FlashBoard board;
  Node<FlashBoard> node(board, kSerial);
  node.boot(0);
  ASSERT_TRUE(SaveCalibration(node, 0.1f, 1000));  // A, generation 1
  ASSERT_TRUE(SaveCalibration(node, 0.2f, 2000));  // B, generation 2: the next save goes to A
  CutEverywhere(board.flash.bytes(), 0.2f, CorrectionFor(0.2f), 1, 0);
}

// Slot A as vesica-calibrate 1.2 stored it on emulated arm 1 (protocol 1.2, image layout 1): the
// sample report's local copy, docs/calibration/sample/arm1-stored.vcal, as it was before layout 2.
constexpr std::uint8_t kLayout1SlotOfArm1[] = {
    0x56, 0x43, 0x53, 0x31, 0x01, 0x00, 0x24, 0x01, 0x01, 0x00, 0x00, 0x00, 0x80, 0x3B, 0xB1, 0x6A, 0x00, 0x01, 0x00,
    0x00, 0x01, 0xCA, 0x51, 0x5E, 0x56, 0x53, 0x50, 0x31, 0x01, 0x00, 0x46, 0x00, 0x01, 0x00, 0x00, 0x00, 0xB8, 0x0B,
    0x00, 0x00, 0x64, 0x00, 0x00, 0x00, 0x0A, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x40, 0x00, 0x00, 0xC0, 0x3F, 0x00,
    0x00, 0x20, 0x41, 0x00, 0x00, 0x40, 0x42, 0x00, 0x00, 0xA0, 0x42, 0x00, 0x00, 0x40, 0x40, 0x00, 0x00, 0x40, 0x40,
    0x00, 0x00, 0xA0, 0x40, 0xFE, 0x65, 0xF7, 0x3C, 0xFE, 0x65, 0xF7, 0x3C, 0x65, 0x19, 0xE2, 0x3C, 0x00, 0x00, 0x60,
    0x41, 0x00, 0x00, 0x60, 0x41, 0x00, 0x00, 0xC8, 0x42, 0x9A, 0x99, 0x99, 0x3F, 0x9A, 0x99, 0x99, 0x3F, 0x00, 0x00,
    0x20, 0x41, 0x00, 0x00, 0xC0, 0x40, 0x00, 0x00, 0xC0, 0x40, 0x00, 0x00, 0x80, 0x3F, 0xDB, 0x1B, 0x88, 0xBF, 0xCF,
    0x66, 0x81, 0xBF, 0x51, 0x45, 0xAA, 0x3C, 0xDB, 0x1B, 0x88, 0x3F, 0xCF, 0x66, 0x81, 0x3F, 0x37, 0x32, 0x7F, 0x3E,
    0x89, 0xD2, 0xEE, 0xBE, 0xBB, 0x96, 0xC0, 0xBE, 0xB1, 0xE6, 0x70, 0x3E, 0x06, 0x87, 0x20, 0x3D, 0xA3, 0x81, 0xD1,
    0x3C, 0x1A, 0x33, 0x4A, 0x3D, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0x10, 0xE0,
    0xC9, 0x3C, 0x0A, 0xC7, 0x36, 0x3E, 0xB8, 0xE7, 0x11, 0x3E, 0x29, 0xB8, 0x38, 0x3C, 0xEC, 0x82, 0xBE, 0x3B, 0x5A,
    0x5E, 0x9F, 0x3E, 0x10, 0x76, 0x21, 0x3B, 0xB5, 0x30, 0x9A, 0x3B, 0xD6, 0x4E, 0xB9, 0x3F, 0x0C, 0x88, 0xD9, 0xBC,
    0xD0, 0x11, 0xF4, 0xBB, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x01, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,
    0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,
    0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,
    0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0xFF, 0x00, 0x00, 0x00, 0x01, 0x00, 0x00, 0x00, 0x01, 0x00, 0x00, 0x00,
    0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x2F, 0x7A, 0x55, 0xB2, 0x77, 0xAE, 0x2F, 0xC7,
};

std::vector<std::uint8_t> FlashWithLayout1SlotA() {
  static_assert(sizeof kLayout1SlotOfArm1 == slot::kLayout1Size);
  std::vector<std::uint8_t> flash(2 * slot::kStride, 0xFF);
  std::copy(std::begin(kLayout1SlotOfArm1), std::end(kLayout1SlotOfArm1), flash.begin());
  return flash;
}

TEST(CalibrationStorageTest, ALayout1SlotOfA1Point2ToolBootsMigratedWithNeutralDefaults) {
  Booted b(FlashWithLayout1SlotA());
  EXPECT_EQ(b.node.latched_fault(), FaultCode::None);
  ASSERT_EQ(b.node.active_slot(), 0);
  EXPECT_EQ(b.node.stored_layout(), 1);
  EXPECT_EQ(ReadU32(b.node, param::kStoredLayout), 1u);
  EXPECT_EQ(b.node.slot_status(0), StorageResult::Ok);
  EXPECT_EQ(b.node.slot_generation(0), 1u);
  EXPECT_EQ(ReadU32(b.node, param::kCalibrationDate_s), 1790000000u);
  EXPECT_EQ(ReadU32(b.node, param::kCalibrationToolVersion), 0x000100u);
  // What the 1.2 tool measured, bit for bit (read off the file with a hex dump).
  EXPECT_EQ(ReadU32(b.node, param::kPositionOffset + 0), 0xBEEED289u);  // -0.46645 rad
  EXPECT_EQ(ReadU32(b.node, param::kCoulombFriction + 1), 0x3BBE82ECu);
  EXPECT_EQ(ReadU32(b.node, param::kGravityCos), 0xBBF411D0u);
  EXPECT_EQ(static_cast<std::int32_t>(ReadU32(b.node, param::kEncoderDirection + 0)), -1);
  // What layout 1 did not have: neutral.
  for (int j = 0; j < 3; ++j)
    EXPECT_EQ(b.node.parameters().f32(static_cast<std::uint16_t>(param::kTorqueConstantCorrection + j)), 1.0f);
  EXPECT_EQ(b.node.parameters().f32(param::kRollSensorOffset), 0.0f);
  EXPECT_EQ(b.node.parameters().u32(param::kJawClosedCounts), b.node.parameters().u32(param::kJawOpenCounts));
  EXPECT_EQ(b.node.parameters().u32(param::kPedalReleasedCounts), b.node.parameters().u32(param::kPedalPressedCounts));
  // The next save keeps slot A and writes layout 2 into B, the migrated values with it.
  ASSERT_TRUE(SaveCalibration(b.node, 0.4f, 4000));
  Booted again(b.board.flash.bytes());
  EXPECT_EQ(again.node.active_slot(), 1);
  EXPECT_EQ(again.node.stored_layout(), 2);
  EXPECT_EQ(again.node.slot_status(0), StorageResult::Ok);  // the 1.2 slot stays, older
  EXPECT_EQ(ReadU32(again.node, param::kCoulombFriction + 0), ReadU32(b.node, param::kCoulombFriction + 0));
  EXPECT_FLOAT_EQ(again.node.parameters().f32(param::kTorqueConstantCorrection + 2), CorrectionFor(0.4f));
}

TEST(CalibrationStorageTest, PowerCutAtEveryByteOfALayout2SaveOverALayout1SlotKeepsIt) {
  const std::vector<std::uint8_t> flash = FlashWithLayout1SlotA();
  Booted b(flash);
  ASSERT_EQ(b.node.active_slot(), 0);
  CutEverywhere(flash, b.node.parameters().f32(param::kPositionOffset), 1.0f, 0, 1);
}

TEST(CalibrationStorageTest, FirmwareOfProtocol1Point2HasNoLayout2AndStoresLayout1) {
  FlashBoard board;
  Node<FlashBoard> node(board, kSerial);
  node.emulate_firmware_minor(2);
  node.boot(0);
  const ParameterResponse r =
      Ask(node, {1, ParameterOp::Read, ParameterType::None, param::kTorqueConstantCorrection, 0});
  EXPECT_TRUE(r.aborted);
  EXPECT_EQ(r.raw_value, static_cast<std::uint32_t>(AbortCode::NoSuchParameter));
  EXPECT_FALSE(Ask(node, {1, ParameterOp::Write, ParameterType::F32, param::kPositionOffset, f32_bits(0.3f)}).aborted);
  ASSERT_FALSE(Ask(node, {1, ParameterOp::Save, ParameterType::None, 0, 0}).aborted);
  EXPECT_EQ(node.stored_layout(), 1);
  std::vector<std::uint8_t> a(board.flash.bytes().begin(), board.flash.bytes().begin() + slot::kSize);
  const SlotCheck c = check_slot(a.data(), a.size());
  EXPECT_EQ(c.status, StorageResult::Ok);
  EXPECT_EQ(c.layout, 1);
  EXPECT_EQ(c.size, slot::kLayout1Size);
  // A 1.3 node boots it; a 1.2 node does not boot a layout-2 slot (it names its version).
  Booted newer(board.flash.bytes());
  EXPECT_EQ(newer.node.active_slot(), 0);
  EXPECT_FLOAT_EQ(newer.node.parameters().f32(param::kPositionOffset), 0.3f);
  ASSERT_TRUE(SaveCalibration(newer.node, 0.5f, 5000));  // layout 2 into B
  FlashBoard older_board;
  older_board.flash.bytes() = newer.board.flash.bytes();
  Node<FlashBoard> older(older_board, kSerial);
  older.emulate_firmware_minor(2);
  older.boot(0);
  EXPECT_EQ(older.active_slot(), 0);
  EXPECT_EQ(older.slot_status(1), StorageResult::BadVersion);
  EXPECT_FLOAT_EQ(older.parameters().f32(param::kPositionOffset), 0.3f);
}

TEST(CalibrationStorageTest, ACorruptSlotIsNamedAndTheOtherBooted) {
  FlashBoard board;
  Node<FlashBoard> node(board, kSerial);
  node.boot(0);
  ASSERT_TRUE(SaveCalibration(node, 0.1f, 1000));
  ASSERT_TRUE(SaveCalibration(node, 0.2f, 2000));
  std::vector<std::uint8_t> flash = board.flash.bytes();
  flash[slot::offset(1) + 40] ^= 0x04;  // one bit of the newest slot's parameter image
  Booted b(flash);
  EXPECT_EQ(b.node.active_slot(), 0);
  EXPECT_EQ(b.node.latched_fault(), FaultCode::None);  // a valid calibration is in force
  EXPECT_FLOAT_EQ(b.node.parameters().f32(param::kPositionOffset), 0.1f);
  EXPECT_EQ(ReadU32(b.node, param::kActiveSlot), 0u);
  EXPECT_EQ(ReadU32(b.node, param::kSlotStatus + 1), static_cast<std::uint32_t>(StorageResult::BadCrc));
  EXPECT_EQ(ReadU32(b.node, param::kSlotStatus + 0), static_cast<std::uint32_t>(StorageResult::Ok));
  EXPECT_EQ(ReadU32(b.node, param::kCalibrationDate_s), 1000u);
  // The next save repairs the corrupt slot, not the good one.
  ASSERT_TRUE(SaveCalibration(b.node, 0.3f, 3000));
  EXPECT_EQ(b.node.active_slot(), 1);
  EXPECT_EQ(b.node.slot_generation(1), 2u);  // one more than the newest valid (A, 1)
}

TEST(CalibrationStorageTest, BothSlotsCorruptLatchesParameterCrcOnDefaults) {
  FlashBoard board;
  Node<FlashBoard> node(board, kSerial);
  node.boot(0);
  ASSERT_TRUE(SaveCalibration(node, 0.1f, 1000));
  ASSERT_TRUE(SaveCalibration(node, 0.2f, 2000));
  std::vector<std::uint8_t> flash = board.flash.bytes();
  flash[slot::offset(0) + 10] ^= 0x01;               // header (generation)
  flash[slot::offset(1) + slot::kSize - 1] ^= 0x80;  // CRC
  Booted b(flash);
  EXPECT_EQ(b.node.active_slot(), -1);
  EXPECT_EQ(b.node.latched_fault(), FaultCode::ParameterCrc);
  EXPECT_EQ(b.node.parameters().f32(param::kPositionOffset), 0.0f);
  EXPECT_EQ(b.node.slot_status(0), StorageResult::BadCrc);
  EXPECT_EQ(b.node.slot_status(1), StorageResult::BadCrc);
}

TEST(CalibrationStorageTest, AnImageFromBeforeTheSlotsLoadsAsSlotAAndTheFirstSaveGoesToB) {
  ParameterStore store;
  store.set_internal_f32(param::kPositionOffset, 0.05f);
  std::vector<std::uint8_t> flash(2 * slot::kStride, 0xFF);
  ASSERT_EQ(store.serialize(flash.data(), flash.size(), 1), ParameterStore::kLayout1ImageSize);  // 1.0's layout
  Booted b(flash);
  EXPECT_EQ(b.node.active_slot(), 0);
  EXPECT_EQ(b.node.latched_fault(), FaultCode::None);
  EXPECT_FLOAT_EQ(b.node.parameters().f32(param::kPositionOffset), 0.05f);
  ASSERT_TRUE(SaveCalibration(b.node, 0.4f, 4000));
  EXPECT_EQ(b.node.active_slot(), 1);
  Booted again(b.board.flash.bytes());
  EXPECT_EQ(again.node.active_slot(), 1);
  // The bare image is no slot: reported as such until the next save replaces it.
  EXPECT_EQ(again.node.slot_status(0), StorageResult::BadCrc);
  EXPECT_FLOAT_EQ(again.node.parameters().f32(param::kPositionOffset), 0.4f);
}

TEST(CalibrationStorageTest, FlashModelErasesBeforeProgrammingAndStopsAtTheCut) {
  FlashModel flash(512, 256);
  const std::uint8_t data[4] = {0x12, 0x34, 0x56, 0x78};
  ASSERT_TRUE(flash.Write(10, data, 4));
  EXPECT_EQ(flash.bytes()[10], 0x12);
  EXPECT_EQ(flash.bytes()[0], 0xFF);
  EXPECT_EQ(flash.OperationsFor(10, 4), 256u + 4u);
  flash.CutPowerAfter(256 + 2);  // the whole erase and two bytes
  EXPECT_FALSE(flash.Write(10, data, 4));
  EXPECT_EQ(flash.bytes()[11], 0x34);
  EXPECT_EQ(flash.bytes()[13], 0xFF);       // never programmed
  EXPECT_FALSE(flash.Write(300, data, 1));  // no power: nothing happens
  EXPECT_EQ(flash.bytes()[300], 0xFF);
  std::uint8_t out[4];
  EXPECT_FALSE(flash.Read(510, out, 4));  // past the end of the chip
}

}  // namespace
}  // namespace vesica::fp
