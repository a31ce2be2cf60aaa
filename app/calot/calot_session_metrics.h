#pragma once
// The Calot's triangle step's share of a session record: the columns of SessionMetrics that
// schema version 4 added (app/records/session_metrics.h), filled from the session's metrics.

#include "app/calot/calot_metrics.h"
#include "app/records/session_metrics.h"

namespace vesica::app::calot {

/// Sets calot_step and the Calot fields of `session` from `metrics` (the other fields are left
/// as they are). cvs_time_s is 0 when the view was not reached.
void StoreCalotMetrics(const CalotMetrics& metrics, SessionMetrics& session);

}  // namespace vesica::app::calot
