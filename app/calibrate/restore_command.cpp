// restore: a stored calibration back in force, from the node's other slot (through its local
// copy: protocol 1.1 cannot read a slot's bytes) or from an image file. A file is checked
// (header, CRC, parameter image, serial) before the bus is opened: a bad one changes nothing.
#include <filesystem>

#include "app/calibrate/commands.h"
#include "app/calibrate/exit_codes.h"
#include "app/calibrate/json_views.h"
#include "app/calibrate/open_arm.h"
#include "app/calibrate/stored_calibration.h"
#include "device/calibration/calibration_abort.h"

namespace vesica::app::calibrate {

namespace cal = device::calibration;
using nlohmann::json;

CommandOutcome Restore(ToolSession& s, int arm, const RestoreRequest& request) {
  const std::string who = "arm " + std::to_string(arm);
  StoredImage image;
  std::string source;
  if (!request.file.empty()) {
    ImageFileCheck c = ReadImageFile(request.file);
    if (c.exit_code != kExitOk) return ToolSession::Failure(c.exit_code, c.message, {{"arm", arm}});
    image = std::move(c.image);
    source = request.file;
  }
  OpenedArm a;
  CommandOutcome failure;
  if (!OpenArm(s, arm, &a, &failure)) return failure;
  const cal::NodeInfo& info = a.info;
  if (request.file.empty()) {
    const int slot = request.slot >= 0 ? request.slot : (info.active_slot == 0 ? 1 : 0);
    const auto k = static_cast<std::size_t>(slot);
    if (info.active_slot == slot)
      return ToolSession::Failure(kExitUsage, who + ": slot " + SlotName(slot) + " is already in force; nothing to do",
                                  {{"arm", arm}});
    if (info.slot_status[k] != fp::StorageResult::Ok)
      return ToolSession::Failure(kExitStorage,
                                  who + ": slot " + SlotName(slot) + " is " +
                                      cal::NodeInfo::SlotText(info.slot_status[k]) +
                                      "; nothing was written (restore from a report's image with --file)",
                                  {{"arm", arm}});
    source = s.image_archive() + "/serial-" + SerialText(info.identity.serial).substr(2) + "-gen-" +
             std::to_string(info.slot_generation[k]) + ".vcal";
    ImageFileCheck c = ReadImageFile(source);
    if (c.exit_code == kExitIo)
      return ToolSession::Failure(kExitStorage,
                                  who + ": no local copy of slot " + SlotName(slot) + " (generation " +
                                      std::to_string(info.slot_generation[k]) + ") in " + s.image_archive() +
                                      "; the node cannot send a slot's contents, use --file with the "
                                      "image beside that calibration's report; nothing was written",
                                  {{"arm", arm}});
    if (c.exit_code != kExitOk) return ToolSession::Failure(c.exit_code, c.message, {{"arm", arm}});
    image = std::move(c.image);
  }
  if (image.header.serial != info.identity.serial)
    return ToolSession::Failure(kExitStorage,
                                who + ": " + source + " is the calibration of serial " +
                                    SerialText(image.header.serial) + ", this arm is serial " +
                                    SerialText(info.identity.serial) + "; nothing was written",
                                {{"arm", arm}});
  CommandOutcome o;
  try {
    const StoredImage before = ReadStoredCalibration(*a.link, info);
    s.ui().Note(who + ": restoring the calibration of " + DateText(image.header.date_s) + " (generation " +
                std::to_string(image.header.generation) + ") from " + source);
    a.link->ClearFault();
    WriteToNode(*a.link, image);
    const cal::NodeInfo after_info = cal::ReadNodeInfo(*a.link);
    StoredImage after = ReadStoredCalibration(*a.link, after_info);
    std::string error;
    const std::string copy = s.session_dir() + "/arm" + std::to_string(arm) + "-stored.vcal";
    std::filesystem::create_directories(s.image_archive());
    if (!WriteImageFile(copy, after, &error) ||
        !WriteImageFile(s.image_archive() + "/serial-" + SerialText(after.header.serial).substr(2) + "-gen-" +
                            std::to_string(after.header.generation) + ".vcal",
                        after, &error))
      return ToolSession::Failure(kExitIo, error);
    o.json = {{"command", "restore"},
              {"arm", arm},
              {"ok", true},
              {"source", source},
              {"restored_generation", image.header.generation},
              {"restored_date", DateText(image.header.date_s)},
              {"before", ToJson(ValuesOf(before.params))},
              {"after", ToJson(ValuesOf(after.params))},
              {"node_after", ToJson(after_info, nullptr)},
              {"image_stored", copy}};
    o.text = a.text + ": restored the calibration of " + DateText(image.header.date_s) + " from " + source +
             "\nnow in force: slot " + SlotName(after_info.active_slot) + ", generation " +
             std::to_string(after.header.generation) + "\n" + ValuesText(ValuesOf(after.params));
  } catch (const cal::CalibrationAbort& e) {
    return AbortOutcome(e, "save", arm);
  }
  return o;
}

}  // namespace vesica::app::calibrate
