#include "app/calibrate/calibration_report.h"

#include <cstdio>
#include <fstream>

#include "app/calibrate/json_views.h"
#include "app/calibrate/report_plots.h"
#include "app/calibrate/tool_session.h"

namespace vesica::app::calibrate {

using nlohmann::json;

json ReportJson(const ReportInput& in) {
  json j;
  j["report"] = in.kind;
  j["tool"] = {{"name", "vesica-calibrate"}, {"version", kToolVersionText}};
  j["date_s"] = in.date_s;
  j["date"] = DateText(in.date_s);
  j["arm"] = in.arm;
  j["bus"] = in.bus;
  j["node"] = ToJson(in.info, nullptr);
  j["node"]["state"] = in.state;
  json joints = json::array();
  for (int k = 0; k < 3; ++k)
    if ((in.joints >> k) & 1u) joints.push_back(JointName(k));
  j["joints"] = joints;
  j["before"] = ToJson(in.before);
  j["after"] = in.after ? ToJson(*in.after) : json(nullptr);
  if (in.info_after) j["node_after"] = ToJson(*in.info_after, nullptr);
  if (in.run) {
    json steps = json::array();
    for (std::size_t k = 0; k < in.run->steps.size(); ++k)
      steps.push_back({{"step", InfoOf(in.run->steps[k]).name}, {"bus_time_s", in.run->step_bus_time_s[k]}});
    j["steps"] = steps;
    j["measured"] = ToJson(in.run->result);
    j["checks"] = ToJson(in.run->checks);
    j["all_pass"] = AllPass(in.run->checks);
    j["saved"] = in.run->result.saved;
    j["bus_time_s"] = in.run->bus_time_s;
  }
  return j;
}

namespace {

std::string Escape(const std::string& s) {
  std::string o;
  for (char c : s) {
    if (c == '<')
      o += "&lt;";
    else if (c == '>')
      o += "&gt;";
    else if (c == '&')
      o += "&amp;";
    else
      o += c;
  }
  return o;
}

std::string Num(const json& v) {
  if (!v.is_number()) return Escape(v.dump());
  char b[40];
  std::snprintf(b, sizeof b, "%.6g", v.get<double>());
  return b;
}

std::string Name(const json& v) {
  if (v.is_null()) return "none";
  return Escape(v.is_string() ? v.get<std::string>() : v.dump());
}

}  // namespace

std::string ReportHtml(const json& d) {
  std::string h =
      "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>Vesica arm " + Num(d["arm"]) + " " +
      Name(d["report"]) +
      "</"
      "title>\n<style>body{font-family:sans-serif;margin:2em;max-width:70em}table{border-collapse:collapse;margin:1em "
      "0}"
      "td,th{border:1px solid #bbb;padding:3px 8px;text-align:right}th{background:#eee}td.l{text-align:left}"
      ".pass{color:#176b1f;font-weight:bold}.fail{color:#b00;font-weight:bold}img{max-width:100%}</style></"
      "head><body>\n";
  const json& n = d["node"];
  h += "<h1>Arm " + Num(d["arm"]) + ": " + Name(d["report"]) + "</h1>\n";
  h += "<p>" + Name(d["date"]) + ", vesica-calibrate " + Name(d["tool"]["version"]) + ", " + Name(d["bus"]) + "</p>\n";
  h += "<table><tr><th>node</th><th>serial</th><th>firmware</th><th>protocol</th><th>state</th><th>fault</th>"
       "<th>slot in use</th></tr><tr><td>" +
       Num(n["node"]) + "</td><td>" + Name(n["serial_text"]) + "</td><td>" + Name(n["firmware_version"]) + "</td><td>" +
       Name(n["protocol"]) + "</td><td>" + Name(n["state"]) + "</td><td>" + Name(n["latched_fault"]) + "</td><td>" +
       Name(n["active_slot"]) + "</td></tr></table>\n";
  if (d.contains("checks")) {
    const bool pass = d["all_pass"].get<bool>();
    h += std::string("<h2>Result: <span class=\"") + (pass ? "pass\">PASS" : "fail\">FAIL") + "</span>" +
         (d["saved"].get<bool>() ? ", saved" : ", not saved");
    if (d.contains("node_after") && !d["node_after"]["active_slot"].is_null()) {
      const json& a = d["node_after"];
      const int k = a["active_slot"] == "A" ? 0 : 1;
      h += " in slot " + Name(a["active_slot"]) + " (generation " + Num(a["slots"][k]["generation"]) + ")";
    }
    h += "</h2>\n";
    h += "<p>Steps: ";
    for (const auto& s : d["steps"]) h += Name(s["step"]) + " (" + Num(s["bus_time_s"]) + " s); ";
    h += "bus time " + Num(d["bus_time_s"]) + " s.</p>\n";
    h += "<h2>Measured values and tolerances</h2>\n<table><tr><th>value</th><th>measured</th><th>unit</th><th>min</th>"
         "<th>max</th><th></th></tr>\n";
    for (const auto& c : d["checks"])
      h += "<tr><td class=\"l\">" + Name(c["name"]) + "</td><td>" + Num(c["value"]) + "</td><td class=\"l\">" +
           Name(c["unit"]) + "</td><td>" + Num(c["min"]) + "</td><td>" + Num(c["max"]) + "</td><td class=\"" +
           (c["pass"].get<bool>() ? "pass\">pass" : "fail\">FAIL") + "</td></tr>\n";
    h += "</table>\n";
  }
  h += "<h2>Stored calibration: before and "
       "after</h2>\n<table><tr><th>joint</th><th>value</th><th>before</th><th>after</th>"
       "<th>change</th></tr>\n";
  for (const auto& [joint, values] : d["before"].items()) {
    for (const auto& [key, value] : values.items()) {
      const json after = d["after"].is_null() ? json(nullptr) : d["after"][joint][key];
      std::string change;
      if (after.is_number() && value.is_number()) change = Num(after.get<double>() - value.get<double>());
      h += "<tr><td class=\"l\">";
      h += joint;
      h += "</td><td class=\"l\">";
      h += key;
      h += "</td><td>" + Num(value) + "</td><td>" + (after.is_null() ? "" : Num(after)) + "</td><td>" + change +
           "</td></tr>\n";
    }
  }
  h += "</table>\n";
  if (d.contains("files")) {
    const json& f = d["files"];
    if (f.contains("friction_png"))
      h += "<h2>Friction fit</h2>\n<p>Mean torque of each constant-velocity sweep (dots) and the fitted Coulomb + "
           "viscous line.</p><img src=\"" +
           Name(f["friction_png"]) + "\" alt=\"friction fit\">\n";
    if (f.contains("range_png"))
      h += "<h2>Range sweep</h2>\n<p>Joint positions through the range step (the node's frame at the time) and the "
           "stops they came to rest on (dashed).</p><img src=\"" +
           Name(f["range_png"]) + "\" alt=\"range sweep\">\n";
    h += "<h2>Files</h2>\n<ul>";
    for (const auto& [key, value] : f.items()) h += "<li>" + key + ": " + Name(value) + "</li>";
    h += "</ul>\n";
  }
  h += "</body></html>\n";
  return h;
}

bool WriteReport(const ReportInput& in, const std::string& dir, const std::string& stem, json& doc, ReportFiles* files,
                 std::string* error) {
  ReportFiles f;
  json names = doc.contains("files") ? doc["files"] : json::object();
  doc = ReportJson(in);
  if (in.run && !in.run->steps.empty()) {
    bool friction = false, range = false;
    for (Step s : in.run->steps) {
      friction = friction || s == Step::kFriction;
      range = range || s == Step::kRange;
    }
    if (friction) {
      f.friction_png = dir + "/" + stem + "-friction.png";
      if (!PlotFrictionFit(in.run->result, in.joints, f.friction_png, error)) return false;
      names["friction_png"] = stem + "-friction.png";
    }
    if (range) {
      f.range_png = dir + "/" + stem + "-range.png";
      if (!PlotRangeSweep(in.run->range_sweep, in.joints, f.range_png, error)) return false;
      names["range_png"] = stem + "-range.png";
    }
  }
  f.json = dir + "/" + stem + ".json";
  f.html = dir + "/" + stem + ".html";
  names["report_json"] = stem + ".json";
  names["report_html"] = stem + ".html";
  doc["files"] = names;
  std::ofstream js(f.json);
  js << doc.dump(2) << "\n";
  std::ofstream html(f.html);
  html << ReportHtml(doc);
  if (!js || !html) {
    *error = "cannot write the report in " + dir;
    return false;
  }
  if (files) *files = f;
  return true;
}

}  // namespace vesica::app::calibrate
