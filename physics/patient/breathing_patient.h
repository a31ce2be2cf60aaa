#pragma once
// The breathing patient's state (seed section 4): one Update(t) moves every organ for time t, from
// the model's rest state (so the result depends on t and the settings alone, never on how often it
// was called), and Publish() hands a consistent snapshot to the renderer and to the haptic loop
// through wait-free triple buffers, as the dissection scene does.
//
// Settings, breath hold and the capsule push may be changed from any thread; they take effect at
// the next Update. Update and Publish belong to one thread (the physics loop).

#include <Eigen/Core>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <vector>

#include "physics/patient/breathing_patient_model.h"
#include "physics/patient/respiration_signal.h"
#include "physics/patient/rib_motion.h"
#include "physics/scene/triple_buffer.h"

namespace vesica::physics {

struct PatientSnapshot {
  double time_s = 0.0;
  double signal = 0.0;                       ///< M(t) / A, in [-1, 1]
  bool holding = false;                      ///< breath hold requested (the signal fades to 0 then stays)
  double tendon_displacement_m = 0.0;        ///< T(t) (eq. 12), caudal positive; the tendon moves by -T along z
  bool tendon_limited = false;               ///< T was clamped so that the fixed crura stay fixed
  std::vector<RibPose> ribs;                 ///< one per model rib, same order
  std::vector<Eigen::Vector3d> diaphragm_m;  ///< diaphragm lattice elements, world
  std::vector<Eigen::Vector3d> liver_m;      ///< liver lattice elements, world
  /// The same before the needle's capsule push: the breathing alone. The needle's haptics map the
  /// CT through it, so that the capsule's depth under the tip is measured from where the capsule
  /// would be without the needle (physics/needle).
  std::vector<Eigen::Vector3d> liver_breathing_m;
  Eigen::Vector3d tumour_centre_m = Eigen::Vector3d::Zero();
  Eigen::Vector3d coupling_force_N = Eigen::Vector3d::Zero();  ///< sum of the diaphragm's pull on the liver
  int capsule_pushed[3] = {-1, -1, -1};                        ///< liver elements under the needle, -1 when none
  int blocked = 0;  ///< mail moves that would have moved a fixed element (0 unless the model is infeasible)
};

class BreathingPatient {
 public:
  explicit BreathingPatient(std::shared_ptr<const BreathingPatientModel> model);

  // Live settings (the breathing panel of seed 6.2). Any thread.
  void SetRespiration(const RespirationSettings& settings);  ///< validated; frequency keeps the phase
  void HoldBreath();
  void ResumeBreathing();
  /// The needle tip's displacement applied to the three capsule elements nearest tip_m (seed 4.5).
  void PushCapsule(const Eigen::Vector3d& tip_m, const Eigen::Vector3d& displacement_m);
  void ReleaseCapsule();

  /// A recorded liver motion (issue 35: a registration result, physics/registration's
  /// MakePointMotion): the displacement of every liver lattice element (model().liver.lattice
  /// order) at time t.
  using LiverMotion = std::function<std::vector<Eigen::Vector3d>(double t_s)>;
  /// Drives the liver by `motion` instead of ChainMail from the next Update (a scenario setting:
  /// a measured breathing replayed); an empty function gives the liver back to ChainMail. The
  /// diaphragm, ribs and the capsule push go on as before. Physics thread.
  void DriveLiver(LiverMotion motion) { liver_motion_ = std::move(motion); }
  /// Moves every organ for time t (seconds, non-decreasing). Physics thread.
  void Update(double t_s);
  /// The state of the last Update (physics thread).
  [[nodiscard]] const PatientSnapshot& snapshot() const { return snapshot_; }
  /// Hands the last Update to both readers.
  void Publish();
  [[nodiscard]] TripleBuffer<PatientSnapshot>& render_snapshots() { return render_; }
  [[nodiscard]] TripleBuffer<PatientSnapshot>& haptic_snapshots() { return haptic_; }

  [[nodiscard]] const BreathingPatientModel& model() const { return *model_; }
  /// The current displacements (physics thread; tests check ChainMail bounds on them).
  [[nodiscard]] const std::vector<Eigen::Vector3d>& diaphragm_displacement() const { return u_diaphragm_; }
  [[nodiscard]] const std::vector<Eigen::Vector3d>& liver_displacement() const { return u_liver_; }

 private:
  struct Commands {
    std::optional<RespirationSettings> settings;
    std::optional<bool> hold;  // true: hold, false: resume
    std::optional<std::pair<Eigen::Vector3d, Eigen::Vector3d>> push;
    bool release = false;
  };
  void TakeCommands(double t_s);
  void MoveDiaphragm(double tendon_m);
  void MoveLiver();
  void LiverLiftsDiaphragm();
  void KeepLiverUnderDiaphragm();
  void PushLiverCapsule();

  std::shared_ptr<const BreathingPatientModel> model_;
  RespirationSettings settings_;
  RespirationSignal signal_;
  std::optional<std::pair<Eigen::Vector3d, Eigen::Vector3d>> push_;
  std::mutex commands_mutex_;
  Commands commands_;

  std::vector<Eigen::Vector3d> u_diaphragm_, u_liver_;
  std::vector<Eigen::Vector3d> targets_;
  std::vector<int> drivers_, cap_drivers_;
  std::vector<Eigen::Vector3d> cap_targets_;
  std::vector<double> lift_;
  LiverMotion liver_motion_;  // empty: ChainMail moves the liver
  PatientSnapshot snapshot_;
  TripleBuffer<PatientSnapshot> render_, haptic_;
};

}  // namespace vesica::physics
