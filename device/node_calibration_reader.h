#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "device/arm_calibration.h"
#include "device/calibration/node_info.h"
#include "firmware_protocol/codec/messages.h"

namespace vesica::device {

/// Reads the calibration an arm's node has in force, inside the bridge's servo cycle: the same
/// parameters `vesica-calibrate info` reads (calibration::NodeInfo: the booted slot, both slots'
/// state, the calibrating tool's version) and the compensation terms (ArmCalibration), one
/// parameter read per call so the 1 kHz cycle never waits. A calibration is valid when the node
/// booted a slot that a calibration tool wrote (tool version not 0: the emulator's and a new
/// board's factory slot that only carries a node id is no calibration) and its values are in
/// range. Not thread-safe: the bridge calls it under its lock.
class NodeCalibrationReader {
 public:
  enum class State { kReading, kValid, kInvalid };

  /// Forget what was read and read again (a new session with the node).
  void Restart();
  /// The next read to send at now_ns, or none: one read is in flight at a time (asked again after
  /// retry_ns without an answer), reads are at least spacing_ns apart, and none once reading is over.
  std::optional<fp::ParameterRequest> NextRequest(std::uint8_t node, std::int64_t now_ns, std::int64_t retry_ns,
                                                  std::int64_t spacing_ns);
  /// A parameter response of the node; true when it answered one of these reads.
  bool Accept(const fp::ParameterResponse& response);

  State state() const { return state_; }
  /// Valid only in state kValid.
  const ArmCalibration& calibration() const { return calibration_; }
  /// The slots as read (meaningful once reading is over).
  const calibration::NodeInfo& stored_slots() const { return stored_slots_; }
  /// Why the calibration is not valid, in words ("slot A: blank, slot B: blank"); empty otherwise.
  const std::string& problem() const { return problem_; }

 private:
  void Evaluate();

  static constexpr int kReadCount = 22;
  State state_ = State::kReading;
  std::uint32_t answered_ = 0;  ///< bit k: read k answered
  std::uint32_t raw_[kReadCount] = {};
  int pending_ = -1;            ///< the read in flight
  std::int64_t asked_ns_ = -1;  ///< when it was sent
  std::uint16_t refused_index_ = 0;
  std::uint32_t refused_code_ = 0;
  ArmCalibration calibration_;
  calibration::NodeInfo stored_slots_;
  std::string problem_;
};

}  // namespace vesica::device
