#include "app/calibrate/json_views.h"

#include <cstdio>
#include <ctime>

namespace vesica::app::calibrate {

namespace cal = device::calibration;
using nlohmann::json;

std::string VersionText(std::uint32_t v) {
  return std::to_string(v >> 16) + "." + std::to_string((v >> 8) & 0xFF) + "." + std::to_string(v & 0xFF);
}

std::string DateText(std::uint32_t s) {
  if (s == 0) return "unknown";
  const std::time_t t = static_cast<std::time_t>(s);
  std::tm tm{};
  gmtime_r(&t, &tm);
  char b[32];
  std::strftime(b, sizeof b, "%Y-%m-%d %H:%M UTC", &tm);
  return b;
}

std::string SerialText(std::uint32_t s) {
  char b[16];
  std::snprintf(b, sizeof b, "0x%08X", s);
  return b;
}

std::string StateText(const NodeHeartbeat* hb) {
  if (!hb) return "state unknown (no heartbeat)";
  return std::string("state ") + fp::to_string(hb->state);
}

json ToJson(const cal::NodeInfo& info, const NodeHeartbeat* hb) {
  json j;
  j["node"] = info.identity.node;
  j["serial"] = info.identity.serial;
  j["serial_text"] = SerialText(info.identity.serial);
  j["firmware_version"] = VersionText(info.firmware_version);
  j["protocol"] = std::to_string(info.identity.protocol_major) + "." + std::to_string(info.identity.max_minor);
  j["protocol_min_minor"] = info.identity.min_minor;
  j["protocol_negotiated_minor"] = info.identity.negotiated_minor;
  j["state"] = hb ? fp::to_string(hb->state) : "unknown";
  j["latched_fault"] = fp::to_string(info.latched_fault);
  j["fault_count"] = info.fault_count;
  json history = json::array();
  for (fp::FaultCode f : info.fault_history) history.push_back(fp::to_string(f));
  j["fault_history"] = history;
  j["active_slot"] = info.active_slot < 0 ? json(nullptr) : json(SlotName(info.active_slot));
  json slots = json::array();
  for (int k = 0; k < 2; ++k)
    slots.push_back({{"slot", SlotName(k)},
                     {"status", cal::NodeInfo::SlotText(info.slot_status[k])},
                     {"valid", info.slot_status[k] == fp::StorageResult::Ok},
                     {"generation", info.slot_generation[k]},
                     {"in_use", info.active_slot == k}});
  j["slots"] = slots;
  j["calibration_date_s"] = info.calibration_date_s;
  j["calibration_date"] = DateText(info.calibration_date_s);
  j["calibration_tool_version"] = VersionText(info.calibration_tool_version);
  j["image_layout"] = info.stored_layout == 0 ? json(nullptr) : json(info.stored_layout);
  j["absent_fields"] = info.AbsentFields();  // a layout-1 image's missing values (neutral defaults)
  return j;
}

json ToJson(const CalibrationValues& v) {
  json j;
  for (int k = 0; k < 3; ++k) {
    const auto& o = v.joint[k];
    j[JointName(k)] = {{"direction", o.direction},
                       {"position_offset", o.position_offset},
                       {"current_offset_A", o.current_offset_A},
                       {"joint_min", o.joint_min},
                       {"joint_max", o.joint_max},
                       {"index_position", o.index_position},
                       {"coulomb", o.coulomb},
                       {"viscous", o.viscous},
                       {"torque_constant_correction", o.torque_constant_correction}};
  }
  j["pitch"]["gravity_sin"] = v.gravity_sin;
  j["pitch"]["gravity_cos"] = v.gravity_cos;
  j["hand"] = {{"roll_sensor_offset_rad", v.roll_sensor_offset_rad},
               {"jaw_closed_counts", v.jaw_closed_counts},
               {"jaw_open_counts", v.jaw_open_counts},
               {"pedal_released_counts", v.pedal_released_counts},
               {"pedal_pressed_counts", v.pedal_pressed_counts}};
  return j;
}

json ToJson(const std::vector<Check>& checks) {
  json a = json::array();
  for (const Check& c : checks)
    a.push_back(
        {{"name", c.name}, {"unit", c.unit}, {"value", c.value}, {"min", c.lo}, {"max", c.hi}, {"pass", c.pass}});
  return a;
}

json ToJson(const cal::CalibrationResult& r) {
  json j;
  for (int k = 0; k < 3; ++k) {
    const auto& c = r.joint[k];
    json segments = json::array();
    for (const auto& s : c.friction_segments) segments.push_back({{"velocity", s.velocity}, {"torque", s.torque}});
    j["joints"][JointName(k)] = {{"direction", c.direction},
                                 {"position_offset", c.position_offset},
                                 {"current_offset_A", c.current_offset_A},
                                 {"lower_stop", c.lower_stop},
                                 {"upper_stop", c.upper_stop},
                                 {"index_position", c.index_position},
                                 {"coulomb", c.coulomb},
                                 {"viscous", c.viscous},
                                 {"friction_offset", c.friction_offset},
                                 {"friction_rms", c.friction_rms},
                                 {"friction_segments", segments}};
    if (c.torque_constant_ratio > 0.0) {  // the check ran
      json holds = json::array();
      for (const auto& h : c.load_holds) holds.push_back({{"position", h.position}, {"torque", h.torque}});
      j["joints"][JointName(k)]["torque_constant_ratio"] = c.torque_constant_ratio;
      j["joints"][JointName(k)]["load_holds"] = holds;
    }
  }
  json holds = json::array();
  for (const auto& h : r.gravity_holds)
    holds.push_back(
        {{"angle_rad", h.angle_rad}, {"breakaway_up", h.breakaway_up}, {"breakaway_down", h.breakaway_down}});
  j["gravity"] = {{"sin", r.gravity_sin}, {"cos", r.gravity_cos}, {"holds", holds}};
  const auto& h = r.hand;  // the guided hand steps, where they ran
  if (h.roll_measured)
    j["hand"]["roll"] = {{"raw", h.roll_raw}, {"offset_rad", h.roll_offset_rad}, {"attempts", h.roll_attempts}};
  if (h.jaw_measured)
    j["hand"]["jaw"] = {{"closed_raw", h.jaw_closed_raw}, {"open_raw", h.jaw_open_raw}, {"attempts", h.jaw_attempts}};
  if (h.pedal_measured)
    j["hand"]["pedal"] = {
        {"released_raw", h.pedal_up_raw}, {"pressed_raw", h.pedal_down_raw}, {"attempts", h.pedal_attempts}};
  j["saved"] = r.saved;
  j["abort"] = cal::ToString(r.abort);
  j["message"] = r.message;
  j["failed_step"] = r.failed_step;
  return j;
}

std::string ChecksText(const std::vector<Check>& checks) {
  std::string s;
  char b[200];
  for (const Check& c : checks) {
    std::snprintf(b, sizeof b, "  %-26s %12.6g %-10s [%.6g, %.6g]  %s\n", c.name.c_str(), c.value, c.unit.c_str(), c.lo,
                  c.hi, c.pass ? "pass" : "FAIL");
    s += b;
  }
  return s;
}

std::string ValuesText(const CalibrationValues& v) {
  std::string s;
  char b[240];
  for (int k = 0; k < 3; ++k) {
    const auto& o = v.joint[k];
    std::snprintf(b, sizeof b,
                  "  %-9s direction %+d  offset %+.5f  range [%+.4f, %+.4f]  index %+.5f  current offset %+.4f A  "
                  "coulomb %.5f  viscous %.5f  torque constant x%.4f\n",
                  JointName(k), o.direction, o.position_offset, o.joint_min, o.joint_max, o.index_position,
                  o.current_offset_A, o.coulomb, o.viscous, o.torque_constant_correction);
    s += b;
  }
  std::snprintf(b, sizeof b, "  gravity   sin %+.5f N m  cos %+.5f N m\n", v.gravity_sin, v.gravity_cos);
  s += b;
  std::snprintf(b, sizeof b, "  hand      roll offset %+.4f rad  jaw %u .. %u counts  pedal %u .. %u counts\n",
                v.roll_sensor_offset_rad, static_cast<unsigned>(v.jaw_closed_counts),
                static_cast<unsigned>(v.jaw_open_counts), static_cast<unsigned>(v.pedal_released_counts),
                static_cast<unsigned>(v.pedal_pressed_counts));
  s += b;
  return s;
}

}  // namespace vesica::app::calibrate
