#pragma once

#include <string>

#include "firmware_protocol/emulator/arm_plant.h"

namespace vesica::app {

/// vesica-armsim --fixture-control: what a technician does to the arm by hand during a
/// calibration, as lines on the process's standard input, so that a calibration over UDP can run
/// the steps that need it (the in-process emulated arm offers the same through its plant):
///
///   reference-load on|off         the reference load fixture clamped on / taken off
///   hand [roll=R] [jaw=J] [pedal=P]  a hand holds the instrument where it is, turns it to roll R
///                                 rad, opens the jaw handle to J rad, presses the pedal P of its
///                                 travel (0..1); moves there over 0.4 s; unnamed values stay
///   let-go                        nobody holds the instrument
///
/// Each line is answered on standard output: "ok LINE" or "error LINE: why".
class FixtureControl {
 public:
  /// Applies one line to the plant; returns the answer.
  std::string Apply(const std::string& line, fp::emulator::ArmPlant& plant);
  /// Reads what standard input has (never waits) and applies each whole line; the answers are
  /// printed. False once standard input is closed.
  bool Poll(fp::emulator::ArmPlant& plant);

 private:
  std::string pending_;
  fp::emulator::HandTarget target_;
  bool holding_ = false;
  bool open_ = true;
};

}  // namespace vesica::app
