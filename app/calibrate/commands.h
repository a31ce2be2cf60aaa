// vesica-calibrate's commands as a library: the command-line program (calibrate_main.cpp) and the
// trainer's Tools > Calibrate panel call the same functions with their own ToolUi. Each returns
// its exit code (exit_codes.h), a JSON document with stable keys and a text for a person.
#pragma once

#include <string>

#include "app/calibrate/calibration_steps.h"
#include "app/calibrate/tool_session.h"

namespace vesica::app::calibrate {

/// Every arm the trainer has (nodes 1 and 2): identity, versions, state, faults, slots.
CommandOutcome Scan(ToolSession& s);
/// One arm in full, with its stored calibration's values.
CommandOutcome Info(ToolSession& s, int arm);

struct CalibrateRequest {
  unsigned joints = 0b111;                  ///< --joint: one bit
  std::vector<Step> steps = AllStepList();  ///< --step: that one only (the rest as stored)
  double max_current_A = 0.6;
};
/// Measures, checks, saves (only when every check passes), then writes the report, the plots and
/// a copy of the stored image into the session folder.
CommandOutcome Calibrate(ToolSession& s, int arm, const CalibrateRequest& request);
/// Measures again without saving and compares with what is stored.
CommandOutcome Verify(ToolSession& s, int arm, const CalibrateRequest& request);

struct RestoreRequest {
  int slot = -1;     ///< 0 A, 1 B; -1: the slot not in use (unless file is given)
  std::string file;  ///< an image file (a report's copy)
};
/// Writes a stored calibration back: from the node's other slot (its copy in the image archive)
/// or from a file. The file is checked before anything is sent.
CommandOutcome Restore(ToolSession& s, int arm, const RestoreRequest& request);
/// A report (JSON + HTML) of the calibration in force, and a copy of its image.
CommandOutcome Report(ToolSession& s, int arm);

struct HomeRequest {
  unsigned joints = 0b111;  ///< --joint: one bit
  double max_current_A = 0.6;
};
/// Protocol 1.4: homes the arm after power-up (device::calibration::HomeArm): the stored
/// calibration in this power-up's frame again; nothing is written to the arm's flash.
CommandOutcome Home(ToolSession& s, int arm, const HomeRequest& request);

}  // namespace vesica::app::calibrate
