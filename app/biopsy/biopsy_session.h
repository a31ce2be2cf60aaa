#pragma once
// One needle-biopsy session (issue 34), without Qt or a clock of its own: the breathing patient,
// the needle's haptics and the trainee's metrics, stepped by Tick() at the haptic rate with the
// stylus' sample. The patient moves every patient_period_s of session time, in the same thread
// and at the same ticks whatever the machine, so a recorded stylus stream replays to the same
// forces and metrics; the needle blends each new patient state in (no force jump).
//
// Tick is cheap (the needle's update) except on the ticks that move the patient (a respiration
// update, under a millisecond).

#include <memory>

#include "app/biopsy/biopsy_patient.h"
#include "app/biopsy/stylus_placement.h"
#include "app/records/session_metrics.h"
#include "device/stylus/stylus_state.h"
#include "physics/needle/needle_haptics.h"
#include "physics/patient/breathing_patient.h"

namespace vesica::app::biopsy {

struct BiopsySessionSettings {
  physics::RespirationSettings respiration;  ///< the patient's breathing at the start
  physics::NeedleHapticsParameters needle;   ///< the needle's force model
  double patient_period_s = 0.02;      ///< > 0: a respiration update every 20 ms (the seed's 20 Hz graphics ran 50 ms)
  bool place_stylus_at_tumour = true;  ///< placement from the tumour (PlacementAtRightSide); else `placement`
  StylusPlacement placement;
  /// A measured breathing for the liver (issue 35: a registration result through
  /// physics::MakePointMotion, LoadLiverMotion): it moves the liver instead of ChainMail. Empty:
  /// ChainMail, as the seed.
  physics::BreathingPatient::LiverMotion liver_motion;
};

/// Throws std::invalid_argument naming the field.
void ValidateBiopsySessionSettings(const BiopsySessionSettings& settings);

class BiopsySession {
 public:
  /// The task's clock starts at 0 s.
  BiopsySession(std::shared_ptr<const BiopsyPatient> patient, BiopsySessionSettings settings = {});

  /// One haptic tick at session time t_s (non-decreasing): moves the patient when its period has
  /// come, computes the needle's force for the stylus' pose, pushes the capsule, and takes the
  /// biopsy on button 1's press. Throws std::invalid_argument for a bad sample or time (nothing
  /// changes).
  const physics::NeedleForces& Tick(const device::StylusState& stylus, double t_s);

  /// The force to send to the device (its frame) for the last tick.
  [[nodiscard]] Eigen::Vector3d DeviceForce() const;
  [[nodiscard]] const physics::NeedlePose& needle_pose() const { return pose_; }
  [[nodiscard]] const physics::NeedleHaptics& needle() const { return needle_; }
  [[nodiscard]] physics::BreathingPatient& patient() { return breathing_; }
  [[nodiscard]] const BiopsyPatient& patient_data() const { return *patient_; }
  [[nodiscard]] const StylusPlacement& placement() const { return settings_.placement; }
  [[nodiscard]] double time_s() const { return time_s_; }
  /// The biopsy is taken: the task is over.
  [[nodiscard]] bool finished() const { return needle_.metrics().sample.has_value(); }

  /// The session's metrics as the records store them (duration up to the last tick, or to the
  /// sample when taken). success: a sample with tumour cells in it (good specimen or some tumour
  /// cells, seed 6.3) and no no-go crossing.
  [[nodiscard]] SessionMetrics Metrics() const;

 private:
  std::shared_ptr<const BiopsyPatient> patient_;
  BiopsySessionSettings settings_;
  physics::BreathingPatient breathing_;
  physics::NeedleHaptics needle_;
  physics::NeedlePose pose_;
  double time_s_ = 0.0;
  double next_patient_update_s_ = 0.0;
  bool button1_was_down_ = false;
  bool ticked_ = false;
  double max_force_N_ = 0.0;
  double force_sum_N_ = 0.0;
  long force_ticks_ = 0;
};

}  // namespace vesica::app::biopsy
