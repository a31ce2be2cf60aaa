#pragma once
// What the emulated surgeon's hand does in vesica-armsim (--hand): hold still, trace a figure
// eight, or play one instrument of a recorded session (the trainer's input recording, e.g. the
// committed data/recordings/dissection.csv), so the instruments in the trainer visibly follow
// the arms. All targets are tip positions in the arm's trocar frame T (origin at the remote
// centre, +z along the mount's reference direction, x = z × world z: app/session/arm_input.h).

#include "device/input/input_frame.h"
#include "firmware_protocol/emulator/hand_model.h"

namespace vesica::app {

namespace emu = fp::emulator;

/// The hand holds the tip at p_T (m) for ever.
emu::HandScript HoldingHand(const emu::Vec3& p_T);

/// A figure eight (Lissajous 1:2) about centre_T in T's x-y plane, `amplitude_m` (> 0) to each
/// side and half that up and down, one loop per `period_s` (> 0), repeated for ever; the jaw
/// opens and closes once per loop (0 .. 0.5 rad) so the grasper's jaws move too. Starts at the
/// centre, so an arm parked there moves off smoothly.
emu::HandScript FigureEightHand(const emu::Vec3& centre_T, double amplitude_m = 0.025, double period_s = 6.0);

/// The tip (T frame, m) of an instrument at `pose` as the trainer measures it from an arm: the
/// trainer's yaw turns about world z and its pitch changes the elevation, both from the mount's
/// reference direction, whose elevation above the horizontal is `reference_elevation_rad`
/// (|.| < pi/2; the azimuth drops out because T turns with the reference). The insertion is
/// kept at least `min_insertion_m` so the shaft's direction stays defined.
emu::Vec3 TipInTrocarFrame(const physics::InstrumentPose& pose, double reference_elevation_rad,
                           double min_insertion_m = 0.02);

/// The recorded instrument `instrument` (device::kLeft or kRight) of `recording` as a hand
/// script: from start_T the hand moves to the first recorded tip over lead_in_s, plays the
/// recording at its own pace (tip, roll, jaw, pedal), returns to the first tip over lead_in_s,
/// and repeats from there for ever. Throws std::invalid_argument for an empty recording, a bad
/// instrument index or an elevation outside (-pi/2, pi/2).
emu::HandScript RecordedHand(const device::InputRecording& recording, int instrument, double reference_elevation_rad,
                             const emu::Vec3& start_T, double lead_in_s = 2.0);

}  // namespace vesica::app
