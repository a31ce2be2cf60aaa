#pragma once
// Deterministic session records for the store tests: every field set away from its default,
// different for each index, with doubles that do not have short decimal forms.

#include "app/records/session_record.h"

namespace vesica::app::testing {

/// Record number `index` of trainee `trainee_id`; started_unix_s = 1795406400 + 600 * index.
SessionRecord SampleRecord(int index, const std::string& trainee_id = "trainee-7");

}  // namespace vesica::app::testing
