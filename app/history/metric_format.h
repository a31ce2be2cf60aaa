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

/// A length in metres as millimetres with one decimal: 0.0072 -> "7.2".
std::string FormatMillimetres(double metres);

/// What a biopsy taken this far from the tumour's centre yields, by the seed paper's bands
/// (section 6.3): < 5 mm "necrotic debris", 5-10 mm "good specimen", 10-15 mm "some tumour
/// cells", > 15 mm "not pathologic". A band's lower bound belongs to it (5.0 mm is good).
std::string FormatSpecimen(double sample_distance_m);

/// A biopsy's outcome: "yes (good specimen)", "no (no sample)", "no (necrotic debris)", ...
/// from metrics.success, biopsy_sampled and sample_distance_m.
std::string FormatBiopsyOutcome(const SessionMetrics& metrics);

/// "yes" or "no" (from metrics.success) with the reason in brackets:
/// "yes (gallbladder free, no perforation)", "no (not free)", "no (perforated)",
/// "no (not free, perforated)"; with the Calot step, its failure too: "no (not free, bile duct
/// injury)", "no (Calot step failed)".
std::string FormatOutcome(const SessionMetrics& metrics);

// The Calot's triangle step (metrics.calot_step; each gives "–" for a session without it).

/// The critical view of safety: "yes at 01:05, before the first clip", "yes at 02:10, after the
/// first clip" or "no".
std::string FormatCriticalView(const SessionMetrics& metrics);

/// A structure's clips: "3 (placed correctly)" or "1 (misplaced)".
std::string FormatClips(int clips, bool placed_correctly);

/// Division of the cystic duct and artery: "both between clips", "duct not between clips",
/// "artery not between clips", "neither between clips" (not divided counts as not between).
std::string FormatDivision(const SessionMetrics& metrics);

/// The Calot step's outcome: "passed", "failed (bile duct injury)" or "failed".
std::string FormatCalotOutcome(const SessionMetrics& metrics);

/// The history table's short critical-view cell: "yes", "late" (after the first clip), "no".
std::string FormatCriticalViewShort(const SessionMetrics& metrics);

}  // namespace vesica::app
