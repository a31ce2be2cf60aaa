#pragma once
// The breathing panel of the biopsy paper (section 6.2, Fig. 14a): the breathing frequency f
// (quiet breathing to hyperventilation), the diaphragm's travel d_max (eq. 12), the thoracic scale
// (alpha_max and beta_max of eqs. 10-11), and breath hold. Each change is handed to `apply` at once.

#include <QWidget>
#include <functional>

#include "physics/patient/respiration_signal.h"

class QDoubleSpinBox;
class QPushButton;

namespace vesica::app::needle_mode {

class BreathingPanel : public QWidget {
 public:
  BreathingPanel(const physics::RespirationSettings& initial,
                 std::function<void(const physics::RespirationSettings&)> apply, std::function<void(bool)> hold,
                 QWidget* parent = nullptr);

  [[nodiscard]] physics::RespirationSettings settings() const;
  [[nodiscard]] bool holding() const;
  /// As the button (and the H key) do.
  void SetHolding(bool holding);
  QDoubleSpinBox* frequency() const { return frequency_; }
  QDoubleSpinBox* travel() const { return travel_; }
  QDoubleSpinBox* thoracic() const { return thoracic_; }
  QPushButton* hold_button() const { return hold_; }

 private:
  void Apply();

  physics::RespirationSettings settings_;
  std::function<void(const physics::RespirationSettings&)> apply_;
  std::function<void(bool)> hold_callback_;
  QDoubleSpinBox* frequency_ = nullptr;
  QDoubleSpinBox* travel_ = nullptr;
  QDoubleSpinBox* thoracic_ = nullptr;
  QPushButton* hold_ = nullptr;
};

}  // namespace vesica::app::needle_mode
