#include "app/needle_mode/breathing_panel.h"

#include <QDoubleSpinBox>
#include <QFormLayout>
#include <QPushButton>

namespace vesica::app::needle_mode {

BreathingPanel::BreathingPanel(const physics::RespirationSettings& initial,
                               std::function<void(const physics::RespirationSettings&)> apply,
                               std::function<void(bool)> hold, QWidget* parent)
    : QWidget(parent), settings_(initial), apply_(std::move(apply)), hold_callback_(std::move(hold)) {
  auto* form = new QFormLayout(this);
  // Quiet breathing 12-18 breaths a minute (0.2-0.3 Hz); hyperventilation up to about 40 (0.65 Hz).
  frequency_ = new QDoubleSpinBox(this);
  frequency_->setObjectName("breathing_frequency");
  frequency_->setRange(0.1, 0.7);
  frequency_->setSingleStep(0.05);
  frequency_->setDecimals(2);
  frequency_->setSuffix(" Hz");
  frequency_->setValue(initial.frequency_Hz);
  travel_ = new QDoubleSpinBox(this);
  travel_->setObjectName("breathing_dmax");
  travel_->setRange(0.0, 40.0);
  travel_->setSingleStep(1.0);
  travel_->setDecimals(0);
  travel_->setSuffix(" mm");
  travel_->setValue(initial.tendon_amplitude_m * 1e3);
  thoracic_ = new QDoubleSpinBox(this);
  thoracic_->setObjectName("breathing_thoracic");
  thoracic_->setRange(0.0, 2.0);
  thoracic_->setSingleStep(0.1);
  thoracic_->setDecimals(1);
  thoracic_->setValue(initial.thoracic_scale);
  hold_ = new QPushButton("Hold breath (H)", this);
  hold_->setObjectName("breath_hold");
  hold_->setCheckable(true);
  form->addRow("Frequency f:", frequency_);
  form->addRow("Diaphragm d_max:", travel_);
  form->addRow("Thoracic scale:", thoracic_);
  form->addRow(hold_);
  for (QDoubleSpinBox* box : {frequency_, travel_, thoracic_})
    connect(box, qOverload<double>(&QDoubleSpinBox::valueChanged), this, [this] { Apply(); });
  connect(hold_, &QPushButton::toggled, this, [this](bool on) {
    hold_->setText(on ? "Breathe (H)" : "Hold breath (H)");
    if (hold_callback_) hold_callback_(on);
  });
}

physics::RespirationSettings BreathingPanel::settings() const { return settings_; }

bool BreathingPanel::holding() const { return hold_->isChecked(); }

void BreathingPanel::SetHolding(bool holding) { hold_->setChecked(holding); }

void BreathingPanel::Apply() {
  settings_.frequency_Hz = frequency_->value();
  settings_.tendon_amplitude_m = travel_->value() * 1e-3;
  settings_.thoracic_scale = thoracic_->value();
  if (apply_) apply_(settings_);
}

}  // namespace vesica::app::needle_mode
