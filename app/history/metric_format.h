#pragma once
// How session metrics read on screen: SI values from SessionMetrics turned into the units a
// trainee reads (mm:ss, cm, mm², N, %). The number functions return the number alone (the
// table puts the unit in its header); the metrics panel appends the unit. Qt-free, so the
// command-line tools can print the same text.

#include <string>

#include "app/records/session_metrics.h"

namespace vesica::app {

/// "mm:ss" of a time in seconds, rounded to the nearest second; minutes are not wrapped at 60
/// ("75:03"). Negative or non-finite input gives "--:--".
std::string FormatMinutesSeconds(double seconds);

/// A length in metres as centimetres with one decimal: 1.2345 -> "123.5".
std::string FormatCentimetres(double metres);

/// An area in m² as mm² with one decimal: 1.25e-5 -> "12.5".
std::string FormatSquareMillimetres(double square_metres);

/// A force in newtons with two decimals: 3.14159 -> "3.14".
std::string FormatNewtons(double newtons);

/// A fraction 0..1 as a percentage with one decimal: 0.4567 -> "45.7".
std::string FormatPercent(double fraction);

/// "yes" or "no" (from metrics.success) with the reason in brackets:
/// "yes (gallbladder free, no perforation)", "no (not free)", "no (perforated)",
/// "no (not free, perforated)".
std::string FormatOutcome(const SessionMetrics& metrics);

}  // namespace vesica::app
