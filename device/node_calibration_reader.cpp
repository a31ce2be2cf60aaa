#include "device/node_calibration_reader.h"

#include <cmath>
#include <cstdio>

#include "firmware_protocol/node/parameter_store.h"
#include "firmware_protocol/node/parameter_table.h"

namespace vesica::device {
namespace {

namespace param = fp::param;

// What is read, in this order (indices into raw_).
constexpr std::uint16_t kReads[] = {param::kActiveSlot,
                                    param::kCalibrationToolVersion,
                                    param::kSlotStatus + 0,
                                    param::kSlotStatus + 1,
                                    param::kCoulombFriction + 0,
                                    param::kCoulombFriction + 1,
                                    param::kCoulombFriction + 2,
                                    param::kViscousFriction + 0,
                                    param::kViscousFriction + 1,
                                    param::kViscousFriction + 2,
                                    param::kGravitySin,
                                    param::kGravityCos,
                                    param::kTorqueConstant + 0,
                                    param::kTorqueConstant + 1,
                                    param::kTorqueConstant + 2,
                                    param::kGearRatio + 0,
                                    param::kGearRatio + 1,
                                    param::kGearRatio + 2,
                                    param::kCalibrationDate_s,
                                    param::kTorqueConstantCorrection + 0,
                                    param::kTorqueConstantCorrection + 1,
                                    param::kTorqueConstantCorrection + 2};
enum : int {
  kActive,
  kTool,
  kSlotA,
  kSlotB,
  kCoulomb,
  kViscous = kCoulomb + 3,
  kGravSin = kViscous + 3,
  kGravCos,
  kKt,
  kGear = kKt + 3,
  kDate = kGear + 3,
  kCorrection  // protocol 1.3; a node below it has none (neutral 1)
};

fp::StorageResult SlotStatus(std::uint32_t raw) {
  return raw <= 4 ? static_cast<fp::StorageResult>(raw) : fp::StorageResult::BadCrc;
}

std::string Hex(std::uint32_t v) {
  char b[16];
  std::snprintf(b, sizeof b, "0x%04X", v);
  return b;
}

}  // namespace

static_assert(sizeof(kReads) / sizeof(kReads[0]) == 22);

void NodeCalibrationReader::Restart() {
  state_ = State::kReading;
  answered_ = 0;
  pending_ = -1;
  asked_ns_ = -1;
  refused_index_ = 0;
  refused_code_ = 0;
  problem_.clear();
}

std::optional<fp::ParameterRequest> NodeCalibrationReader::NextRequest(std::uint8_t node, std::int64_t now_ns,
                                                                       std::int64_t retry_ns, std::int64_t spacing_ns) {
  if (state_ != State::kReading) return std::nullopt;
  // One read in flight: the next once it is answered (or asked again after retry_ns), and
  // never two within spacing_ns, so reading leaves the bus to the servo traffic.
  const bool waiting = pending_ >= 0 && ((answered_ >> pending_) & 1u) == 0;
  if (waiting && now_ns - asked_ns_ < retry_ns) return std::nullopt;
  if (asked_ns_ >= 0 && now_ns - asked_ns_ < spacing_ns) return std::nullopt;
  int k = 0;
  while (k < kReadCount && ((answered_ >> k) & 1u) != 0) ++k;
  if (k >= kReadCount) return std::nullopt;
  pending_ = k;
  asked_ns_ = now_ns;
  return fp::ParameterRequest{node, fp::ParameterOp::Read, fp::ParameterType::None, kReads[k], 0};
}

bool NodeCalibrationReader::Accept(const fp::ParameterResponse& r) {
  if (state_ != State::kReading || r.op != fp::ParameterOp::Read) return false;
  for (int k = 0; k < kReadCount; ++k) {
    if (kReads[k] != r.index) continue;
    const int spec = fp::parameter_slot(r.index);
    if (r.aborted && r.raw_value == static_cast<std::uint32_t>(fp::AbortCode::NoSuchParameter) && spec >= 0 &&
        fp::parameter_layout(static_cast<std::size_t>(spec)) > 1) {
      // A node below protocol 1.3 stores no layout-2 value: its neutral default.
      raw_[k] = fp::f32_bits(static_cast<float>(fp::kParameterSpecs[spec].default_value));
      answered_ |= 1u << k;
      if (answered_ == (1u << kReadCount) - 1u) Evaluate();
      return true;
    }
    if (r.aborted) {
      refused_index_ = r.index;
      refused_code_ = r.raw_value;
      Evaluate();
      return true;
    }
    raw_[k] = r.raw_value;
    answered_ |= 1u << k;
    if (answered_ == (1u << kReadCount) - 1u) Evaluate();
    return true;
  }
  return false;
}

void NodeCalibrationReader::Evaluate() {
  state_ = State::kInvalid;
  if (refused_code_ != 0) {
    const fp::ParameterSpec* spec = fp::find_parameter(refused_index_);
    const std::string name = spec ? spec->name : Hex(refused_index_);
    problem_ = refused_code_ == static_cast<std::uint32_t>(fp::AbortCode::NoSuchParameter)
                   ? "the node's firmware keeps no calibration (no parameter " + name + "); update it"
                   : "the node refused to read " + name + " (abort code " + Hex(refused_code_) + ")";
    return;
  }
  stored_slots_.active_slot = raw_[kActive] < 2 ? static_cast<int>(raw_[kActive]) : -1;
  stored_slots_.slot_status = {SlotStatus(raw_[kSlotA]), SlotStatus(raw_[kSlotB])};
  stored_slots_.calibration_tool_version = raw_[kTool];
  stored_slots_.calibration_date_s = raw_[kDate];
  if (stored_slots_.active_slot < 0) {
    problem_ = "slot A: " + calibration::NodeInfo::SlotText(stored_slots_.slot_status[0]) +
               ", slot B: " + calibration::NodeInfo::SlotText(stored_slots_.slot_status[1]);
    return;
  }
  const std::string slot = stored_slots_.active_slot == 0 ? "A" : "B";
  if (stored_slots_.calibration_tool_version == 0) {
    problem_ = "slot " + slot + " holds settings only, written by no calibration";
    return;
  }
  ArmCalibration c;
  auto value = [&](int k) { return static_cast<double>(fp::bits_f32(raw_[k])); };
  for (int j = 0; j < 3; ++j) {
    c.coulomb[j] = value(kCoulomb + j);
    c.viscous[j] = value(kViscous + j);
    c.effort_per_amp[j] = value(kKt + j) * value(kGear + j);
    c.torque_constant_correction[j] = value(kCorrection + j);
    if (!(c.torque_constant_correction[j] >= 0.5 && c.torque_constant_correction[j] <= 2.0)) {
      problem_ = std::string("slot ") + slot + ": the " +
                 (j == 0   ? "yaw"
                  : j == 1 ? "pitch"
                           : "insertion") +
                 " torque-constant correction is out of range";
      return;
    }
    const char* joint = j == 0 ? "yaw" : j == 1 ? "pitch" : "insertion";
    if (!(c.coulomb[j] >= 0.0 && std::isfinite(c.coulomb[j]) && c.viscous[j] >= 0.0 && std::isfinite(c.viscous[j]))) {
      problem_ = std::string("slot ") + slot + ": the " + joint + " friction is out of range";
      return;
    }
    if (!(c.effort_per_amp[j] > 0.0 && std::isfinite(c.effort_per_amp[j]))) {
      problem_ = std::string("slot ") + slot + ": the " + joint + " torque constant or gear ratio is out of range";
      return;
    }
  }
  c.gravity_sin = value(kGravSin);
  c.gravity_cos = value(kGravCos);
  if (!std::isfinite(c.gravity_sin) || !std::isfinite(c.gravity_cos)) {
    problem_ = "slot " + slot + ": the pitch gravity is out of range";
    return;
  }
  calibration_ = c;
  state_ = State::kValid;
}

}  // namespace vesica::device
