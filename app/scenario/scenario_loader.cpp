#include "app/scenario/scenario_loader.h"

#include <toml++/toml.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <functional>
#include <optional>
#include <set>
#include <sstream>
#include <utility>

namespace vesica::app {

namespace {

namespace fs = std::filesystem;

/// The shortest text that reads back to the same double, so that a value refused for being out of
/// range never prints as an allowed one (0.50000000001, not 0.5).
std::string Shortest(double v) {
  std::array<char, 32> buf{};
  const auto end = std::to_chars(buf.data(), buf.data() + buf.size(), v).ptr;
  return std::string(buf.data(), end);
}

/// Reads one TOML table, remembering which keys were used so that unknown keys (typos) are errors.
/// Every message carries file, line and the dotted key.
class TableReader {
 public:
  TableReader(const toml::table& table, std::string file, std::string prefix)
      : table_(table), file_(std::move(file)), prefix_(std::move(prefix)) {}

  [[noreturn]] void Fail(const toml::node* at, std::string_view key, const std::string& what) const {
    std::ostringstream os;
    const auto& where = at ? at->source() : table_.source();
    os << file_ << ':' << where.begin.line << ": " << Dotted(key) << ": " << what;
    throw ScenarioError(os.str());
  }

  const toml::node* Node(std::string_view key) {
    used_.insert(std::string(key));
    return table_.get(key);
  }

  double Number(std::string_view key, std::optional<double> fallback = std::nullopt) {
    const toml::node* n = Node(key);
    if (!n) {
      if (fallback) return *fallback;
      Fail(nullptr, key, "missing (a number is required)");
    }
    if (auto v = n->value<double>(); v && n->is_number()) {
      if (!std::isfinite(*v)) Fail(n, key, "must be a finite number, got " + Shortest(*v));
      return *v;
    }
    Fail(n, key, std::string("must be a number, got ") + TypeName(*n));
  }

  /// A number in the open interval (lo, hi); infinities allowed as open ends.
  double NumberIn(std::string_view key, double lo, double hi, std::optional<double> fallback = std::nullopt) {
    const double v = Number(key, fallback);
    if (!(v > lo && v < hi))
      Fail(table_.get(key), key, "must be in (" + Shortest(lo) + ", " + Shortest(hi) + "), got " + Shortest(v));
    return v;
  }

  double Positive(std::string_view key, std::optional<double> fallback = std::nullopt) {
    const double v = Number(key, fallback);
    if (!(v > 0)) Fail(table_.get(key), key, "must be > 0, got " + Shortest(v));
    return v;
  }

  double NonNegative(std::string_view key, std::optional<double> fallback = std::nullopt) {
    const double v = Number(key, fallback);
    if (!(v >= 0)) Fail(table_.get(key), key, "must be >= 0, got " + Shortest(v));
    return v;
  }

  std::string String(std::string_view key, std::optional<std::string> fallback = std::nullopt) {
    const toml::node* n = Node(key);
    if (!n) {
      if (fallback) return *fallback;
      Fail(nullptr, key, "missing (a string is required)");
    }
    if (auto v = n->value<std::string>(); v && n->is_string()) return *v;
    Fail(n, key, std::string("must be a string, got ") + TypeName(*n));
  }

  bool Boolean(std::string_view key, bool fallback) {
    const toml::node* n = Node(key);
    if (!n) return fallback;
    if (n->is_boolean()) return *n->value<bool>();
    Fail(n, key, std::string("must be true or false, got ") + TypeName(*n));
  }

  /// An integer in [lo, hi], checked before it is narrowed (4294967297 is not 1).
  int IntegerIn(std::string_view key, int lo, int hi, std::optional<int> fallback = std::nullopt) {
    const toml::node* n = Node(key);
    if (!n) {
      if (fallback) return *fallback;
      Fail(nullptr, key, "missing (an integer is required)");
    }
    if (!n->is_integer()) Fail(n, key, std::string("must be an integer, got ") + TypeName(*n));
    const std::int64_t v = n->as_integer()->get();
    if (v < lo || v > hi)
      Fail(n, key, "must be in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], got " + std::to_string(v));
    return static_cast<int>(v);
  }

  Eigen::Vector3d Vector3(std::string_view key, std::optional<Eigen::Vector3d> fallback = std::nullopt) {
    const toml::node* n = Node(key);
    if (!n) {
      if (fallback) return *fallback;
      Fail(nullptr, key, "missing (an array of 3 numbers is required)");
    }
    const toml::array* a = n->as_array();
    if (!a || a->size() != 3)
      Fail(n, key,
           "must be an array of 3 numbers [x, y, z], got " +
               (a ? "an array of " + std::to_string(a->size()) : std::string(TypeName(*n))));
    Eigen::Vector3d v;
    for (int i = 0; i < 3; ++i) {
      const toml::node& e = (*a)[static_cast<std::size_t>(i)];
      if (!e.is_number()) Fail(n, key, "element " + std::to_string(i) + " must be a number");
      v[i] = *e.value<double>();
      if (!std::isfinite(v[i]))
        Fail(n, key, "element " + std::to_string(i) + " must be a finite number, got " + Shortest(v[i]));
    }
    return v;
  }

  /// An array of [x, y, z] points, at least `min_points`.
  std::vector<Eigen::Vector3d> Vector3List(std::string_view key, std::size_t min_points) {
    const toml::node* n = Node(key);
    if (!n) Fail(nullptr, key, "missing (an array of [x, y, z] points is required)");
    const toml::array* a = n->as_array();
    if (!a || a->size() < min_points)
      Fail(n, key, "must be an array of at least " + std::to_string(min_points) + " [x, y, z] points");
    std::vector<Eigen::Vector3d> points;
    for (std::size_t k = 0; k < a->size(); ++k) {
      const toml::array* p = (*a)[k].as_array();
      if (!p || p->size() != 3) Fail(n, key, "point " + std::to_string(k) + " must be [x, y, z]");
      Eigen::Vector3d v;
      for (int i = 0; i < 3; ++i) {
        const toml::node& e = (*p)[static_cast<std::size_t>(i)];
        if (!e.is_number() || !std::isfinite(*e.value<double>()))
          Fail(n, key, "point " + std::to_string(k) + " element " + std::to_string(i) + " must be a finite number");
        v[i] = *e.value<double>();
      }
      points.push_back(v);
    }
    return points;
  }

  /// An array of strings; empty when the key is absent.
  std::vector<std::string> StringList(std::string_view key) {
    const toml::node* n = Node(key);
    if (!n) return {};
    const toml::array* a = n->as_array();
    if (!a) Fail(n, key, std::string("must be an array of strings, got ") + TypeName(*n));
    std::vector<std::string> out;
    for (std::size_t k = 0; k < a->size(); ++k) {
      const toml::node& e = (*a)[k];
      if (!e.is_string()) Fail(n, key, "element " + std::to_string(k) + " must be a string, got " + TypeName(e));
      out.push_back(*e.value<std::string>());
    }
    return out;
  }

  /// One of the named choices; the message lists them.
  template <typename Enum>
  Enum Choice(std::string_view key, const std::vector<std::pair<std::string, Enum>>& choices,
              std::optional<Enum> fallback = std::nullopt) {
    if (!table_.get(key) && fallback) {
      used_.insert(std::string(key));
      return *fallback;
    }
    const std::string s = String(key);
    std::string names;
    for (const auto& [name, value] : choices) {
      if (name == s) return value;
      names += (names.empty() ? "" : ", ") + name;
    }
    Fail(table_.get(key), key, "unknown value '" + s + "' (expected one of: " + names + ")");
  }

  TableReader Table(std::string_view key) {
    const toml::node* n = Node(key);
    if (!n) Fail(nullptr, key, "missing table [" + Dotted(key) + "]");
    const toml::table* t = n->as_table();
    if (!t) Fail(n, key, std::string("must be a table, got ") + TypeName(*n));
    return TableReader(*t, file_, Dotted(key));
  }

  bool Has(std::string_view key) const { return table_.contains(key); }

  /// [[key]] arrays of tables.
  std::vector<TableReader> Tables(std::string_view key) {
    const toml::node* n = Node(key);
    if (!n) Fail(nullptr, key, "missing (at least one [[" + Dotted(key) + "]] is required)");
    const toml::array* a = n->as_array();
    if (!a || !a->is_array_of_tables()) Fail(n, key, "must be an array of tables [[" + Dotted(key) + "]]");
    std::vector<TableReader> out;
    for (std::size_t i = 0; i < a->size(); ++i)
      out.emplace_back(*(*a)[i].as_table(), file_, Dotted(key) + "[" + std::to_string(i) + "]");
    return out;
  }

  /// Call after reading: any key not read is a typo or an unsupported setting.
  void RejectUnknownKeys() const {
    for (const auto& [k, node] : table_)
      if (!used_.count(std::string(k.str()))) Fail(&node, k.str(), "unknown key");
  }

  const std::string& file() const { return file_; }
  const toml::table& table() const { return table_; }

 private:
  std::string Dotted(std::string_view key) const {
    return prefix_.empty() ? std::string(key) : prefix_ + "." + std::string(key);
  }
  static const char* TypeName(const toml::node& n) {
    switch (n.type()) {
      case toml::node_type::string:
        return "a string";
      case toml::node_type::integer:
        return "an integer";
      case toml::node_type::floating_point:
        return "a number";
      case toml::node_type::boolean:
        return "a boolean";
      case toml::node_type::array:
        return "an array";
      case toml::node_type::table:
        return "a table";
      default:
        return "a date/time";
    }
  }

  const toml::table& table_;
  std::string file_;
  std::string prefix_;
  std::set<std::string> used_;
};

fs::path ExistingFile(TableReader& t, std::string_view key, const fs::path& base_dir) {
  const std::string raw = t.String(key);
  fs::path p = fs::path(raw).is_absolute() ? fs::path(raw) : base_dir / raw;
  p = p.lexically_normal();
  std::error_code ec;
  if (fs::is_directory(p, ec)) t.Fail(t.table().get(key), key, "is a directory, not a file: " + p.string());
  if (!fs::is_regular_file(p, ec)) t.Fail(t.table().get(key), key, "file not found: " + p.string());
  return p;
}

Material ReadMaterial(TableReader& t) {
  Material m;
  m.youngs_modulus_Pa = t.Positive("youngs_modulus_Pa");
  m.poisson_ratio = t.NumberIn("poisson_ratio", -1.0, 0.5);
  m.density_kg_per_m3 = t.Positive("density_kg_per_m3", 1000.0);
  return m;
}

// [calot_triangle]: the variant's name, the neck, and its [[calot_triangle.tubes]].
CalotTriangleConfig ReadCalotTriangle(TableReader t, const std::string& file) {
  using physics::calot::TubeEndHold;
  using physics::calot::TubeKind;
  CalotTriangleConfig c;
  c.variant = t.String("variant");
  c.neck_m = t.Vector3("neck_m");
  c.node_spacing_m = t.NumberIn("node_spacing_m", 0.0005, 0.02, 0.0025);
  int cystic_ducts = 0, common_bile_ducts = 0;
  for (auto& tube : t.Tables("tubes")) {
    CalotTubeConfig u;
    u.name = tube.String("name");
    u.source = file + ":" + std::to_string(tube.table().source().begin.line);
    u.kind = tube.Choice<TubeKind>("kind", {{"cystic_duct", TubeKind::kCysticDuct},
                                            {"cystic_artery", TubeKind::kCysticArtery},
                                            {"common_hepatic_duct", TubeKind::kCommonHepaticDuct},
                                            {"common_bile_duct", TubeKind::kCommonBileDuct}});
    const bool cystic = u.kind == TubeKind::kCysticDuct || u.kind == TubeKind::kCysticArtery;
    u.points_m = tube.Vector3List("points_m", 2);
    u.end = tube.Choice<TubeEndHold>(
        "end", {{"neck", TubeEndHold::kNeck}, {"clamped", TubeEndHold::kClamped}, {"free", TubeEndHold::kFree}},
        cystic ? TubeEndHold::kNeck : TubeEndHold::kClamped);
    if (u.end == TubeEndHold::kNeck && (u.points_m.back() - c.neck_m).norm() > 0.01)
      tube.Fail(tube.table().get("points_m"), "points_m",
                "its last point is " + Shortest((u.points_m.back() - c.neck_m).norm() * 1000) +
                    " mm from neck_m; a tube held at the neck must end within 10 mm of it");
    u.planned_cut_s = tube.NumberIn("planned_cut_s", 0.0, 1.0, 0.6);
    if (tube.Has("outer_radius_m")) u.outer_radius_m = tube.NumberIn("outer_radius_m", 0.0002, 0.01);
    tube.RejectUnknownKeys();
    cystic_ducts += u.kind == TubeKind::kCysticDuct;
    common_bile_ducts += u.kind == TubeKind::kCommonBileDuct;
    c.tubes.push_back(std::move(u));
  }
  // Every variant has a cystic duct and a common bile duct: the step is to tell them apart.
  if (cystic_ducts != 1 || common_bile_ducts != 1)
    t.Fail(t.table().get("tubes"), "tubes",
           "needs exactly one cystic_duct and one common_bile_duct, got " + std::to_string(cystic_ducts) + " and " +
               std::to_string(common_bile_ducts));
  t.RejectUnknownKeys();
  try {
    physics::calot::ValidateTriangleDescription(ToPhysics(c));
  } catch (const std::invalid_argument& e) {
    t.Fail(nullptr, "tubes", e.what());
  }
  return c;
}

}  // namespace

const Trocar& Scenario::trocar(const std::string& trocar_name) const {
  for (const auto& t : trocars)
    if (t.name == trocar_name) return t;
  throw ScenarioError(source.string() + ": no trocar named '" + trocar_name + "'");
}

Scenario ParseScenario(std::string_view text, const fs::path& source_name, const fs::path& base_dir) {
  const std::string file = source_name.string();
  toml::table root;
  try {
    root = toml::parse(text, file);
  } catch (const toml::parse_error& e) {
    std::ostringstream os;
    os << file << ':' << e.source().begin.line << ": syntax error: " << e.description();
    throw ScenarioError(os.str());
  }
  TableReader top(root, file, "");
  Scenario s;
  s.source = source_name;

  {
    auto t = top.Table("scenario");
    s.name = t.String("name");
    s.description = t.String("description", std::string());
    t.RejectUnknownKeys();
  }
  {
    auto t = top.Table("liver");
    t.Choice<int>("model", {{"bem", 0}});
    s.liver.surface_mesh = ExistingFile(t, "surface_mesh", base_dir);
    s.liver.material = ReadMaterial(t);
    t.RejectUnknownKeys();
  }
  {
    auto t = top.Table("gallbladder");
    t.Choice<int>("model", {{"fem", 0}});
    s.gallbladder.volume_mesh = ExistingFile(t, "volume_mesh", base_dir);
    s.gallbladder.material = ReadMaterial(t);
    s.gallbladder.element =
        t.Choice<FemElement>("element", {{"linear", FemElement::kLinear}, {"corotational", FemElement::kCorotational}},
                             FemElement::kCorotational);
    s.gallbladder.solver = t.Choice<FemSolver>("solver",
                                               {{"pcg", FemSolver::kPcg},
                                                {"cholmod", FemSolver::kCholmod},
                                                {"rotated_factor_pcg", FemSolver::kRotatedFactorPcg}},
                                               FemSolver::kPcg);
    s.gallbladder.rayleigh_mass = t.NonNegative("rayleigh_mass_per_s", 0.1);
    s.gallbladder.rayleigh_stiffness = t.NonNegative("rayleigh_stiffness_s", 0.01);
    t.RejectUnknownKeys();
  }
  {
    auto t = top.Table("connective_tissue");
    s.connective_tissue.stiffness_N_per_m = t.Positive("stiffness_N_per_m");
    s.connective_tissue.damping_Ns_per_m = t.NonNegative("damping_Ns_per_m", 0.0);
    s.connective_tissue.attach_offset_m = t.Positive("attach_offset_m", 0.005);
    t.RejectUnknownKeys();
  }
  {
    auto t = top.Table("abdominal_wall");
    s.abdominal_wall.surface_mesh = ExistingFile(t, "surface_mesh", base_dir);
    const double opacity = t.Number("opacity", 0.15);
    if (!(opacity >= 0 && opacity <= 1))
      t.Fail(t.table().get("opacity"), "opacity", "must be in [0, 1], got " + Shortest(opacity));
    s.abdominal_wall.opacity = opacity;
    t.RejectUnknownKeys();
  }
  for (auto& t : top.Tables("trocars")) {
    Trocar trocar;
    trocar.name = t.String("name");
    trocar.position_m = t.Vector3("position_m");
    for (const auto& other : s.trocars)
      if (other.name == trocar.name) t.Fail(t.table().get("name"), "name", "duplicate trocar '" + trocar.name + "'");
    t.RejectUnknownKeys();
    s.trocars.push_back(trocar);
  }
  {
    auto t = top.Table("laparoscope");
    s.laparoscope.position_m = t.Vector3("position_m");
    s.laparoscope.look_at_m = t.Vector3("look_at_m");
    if ((s.laparoscope.look_at_m - s.laparoscope.position_m).norm() < 1e-3)
      t.Fail(t.table().get("look_at_m"), "look_at_m", "must be at least 1 mm from position_m");
    s.laparoscope.insertion_m = t.NumberIn("insertion_m", 0.0, 0.3, 0.07);
    if (s.laparoscope.insertion_m > (s.laparoscope.look_at_m - s.laparoscope.position_m).norm() - 0.01)
      t.Fail(t.table().get("insertion_m"), "insertion_m", "puts the scope's tip within 1 cm of (or past) look_at_m");
    s.laparoscope.view_angle_deg = t.NumberIn("view_angle_deg", 1.0, 179.0, 70.0);
    s.laparoscope.scope_angle_deg = t.NumberIn("scope_angle_deg", -1.0, 90.0, 30.0);
    t.RejectUnknownKeys();
  }
  if (top.Has("context_organs"))
    for (auto& t : top.Tables("context_organs")) {
      ContextOrgan organ;
      organ.name = t.String("name");
      organ.shape = t.Choice<ContextOrgan::Shape>(
          "shape", {{"tube", ContextOrgan::Shape::kTube}, {"ellipsoid", ContextOrgan::Shape::kEllipsoid}});
      if (organ.shape == ContextOrgan::Shape::kTube) {
        organ.points_m = t.Vector3List("points_m", 2);
        organ.radius_m = t.NumberIn("radius_m", 1e-4, 0.1);
      } else {
        organ.centre_m = t.Vector3("centre_m");
        organ.semi_axes_m = t.Vector3("semi_axes_m");
        if (!(organ.semi_axes_m.minCoeff() > 0 && organ.semi_axes_m.maxCoeff() < 0.3))
          t.Fail(t.table().get("semi_axes_m"), "semi_axes_m", "each must be in (0, 0.3) m");
      }
      organ.rgb = t.Vector3("rgb");
      if (!(organ.rgb.minCoeff() >= 0 && organ.rgb.maxCoeff() <= 1))
        t.Fail(t.table().get("rgb"), "rgb", "each component must be in [0, 1]");
      // Bowel, stomach and omentum hold the gallbladder up; ducts, vessels and instruments do not.
      const bool bulky = organ.shape == ContextOrgan::Shape::kEllipsoid || organ.radius_m >= kSolidTubeRadius_m;
      organ.solid = t.Boolean("solid", bulky);
      t.RejectUnknownKeys();
      s.context_organs.push_back(std::move(organ));
    }
  if (top.Has("calot_triangle")) s.calot_triangle = ReadCalotTriangle(top.Table("calot_triangle"), file);
  if (top.Has("patient")) {
    auto t = top.Table("patient");
    s.patient.given = true;
    s.patient.reverse_trendelenburg_deg = t.NumberIn("reverse_trendelenburg_deg", -45.0, 45.0, 0.0);
    s.patient.left_tilt_deg = t.NumberIn("left_tilt_deg", -45.0, 45.0, 0.0);
    s.patient.gravity_m_per_s2 = t.NumberIn("gravity_m_per_s2", 0.0, 20.0, 9.81);
    t.RejectUnknownKeys();
  }
  if (top.Has("assistant_retraction")) {
    auto t = top.Table("assistant_retraction");
    AssistantRetractionConfig r;
    r.grasp_point_m = t.Vector3("grasp_point_m");
    r.radius_m = t.NumberIn("radius_m", 0.001, 0.05, 0.01);
    r.displacement_m = t.Vector3("displacement_m", Eigen::Vector3d::Zero());
    if (!(r.displacement_m.norm() <= 0.05))
      t.Fail(t.table().get("displacement_m"), "displacement_m", "must be at most 0.05 m long");
    r.stiffness_N_per_m = t.Positive("stiffness_N_per_m", 50.0);
    r.damping_Ns_per_m = t.NonNegative("damping_Ns_per_m", 0.05);
    t.RejectUnknownKeys();
    s.assistant_retraction = r;
  }
  for (auto& t : top.Tables("instruments")) {
    InstrumentConfig in;
    in.name = t.String("name");
    in.kind = t.Choice<InstrumentKind>(
        "kind", {{"grasper", InstrumentKind::kGrasper}, {"cautery_hook", InstrumentKind::kCauteryHook}});
    in.trocar = t.String("trocar");
    bool found = false;
    for (const auto& tr : s.trocars) found = found || tr.name == in.trocar;
    if (!found) t.Fail(t.table().get("trocar"), "trocar", "no trocar named '" + in.trocar + "'");
    in.input = t.Choice<InputKind>("input",
                                   {{"keyboard", InputKind::kKeyboard},
                                    {"replay", InputKind::kReplay},
                                    {"emulated_arm", InputKind::kEmulatedArm},
                                    {"can_arm", InputKind::kCanArm}},
                                   InputKind::kKeyboard);
    if (in.input == InputKind::kReplay) in.replay_file = ExistingFile(t, "replay_file", base_dir);
    if (in.input == InputKind::kCanArm || in.input == InputKind::kEmulatedArm) {
      in.can_interface = t.String("can_interface", std::string(in.input == InputKind::kCanArm ? "can0" : "virtual"));
      in.can_node_id = t.IntegerIn("can_node_id", 1, 127);
    }
    for (const std::string& key : t.StringList("exchange")) {
      const std::optional<InstrumentKind> tool = physics::ParseToolKey(key);
      if (!tool || !physics::IsRightHandTool(*tool))
        t.Fail(t.table().get("exchange"), "exchange",
               "unknown tool '" + key + "' (expected cautery_hook, clip_applier or scissors)");
      if (in.kind == InstrumentKind::kGrasper)
        t.Fail(t.table().get("exchange"), "exchange", "the grasper's port keeps the grasper: no exchange");
      if (*tool == in.kind || std::find(in.exchange.begin(), in.exchange.end(), *tool) != in.exchange.end())
        t.Fail(t.table().get("exchange"), "exchange", "lists '" + key + "' twice (the instrument's kind counts)");
      in.exchange.push_back(*tool);
    }
    in.shaft_length_m = t.Positive("shaft_length_m", 0.36);
    in.shaft_radius_m = t.Positive("shaft_radius_m", 0.0025);
    in.initial_insertion_m = t.NonNegative("initial_insertion_m", 0.10);
    if (in.initial_insertion_m > in.shaft_length_m)
      t.Fail(t.table().get("initial_insertion_m"), "initial_insertion_m", "exceeds shaft_length_m");
    for (const auto& other : s.instruments)
      if (other.name == in.name) t.Fail(t.table().get("name"), "name", "duplicate instrument '" + in.name + "'");
    t.RejectUnknownKeys();
    s.instruments.push_back(in);
  }
  top.RejectUnknownKeys();
  return s;
}

Scenario LoadScenario(const fs::path& path) {
  std::error_code ec;
  // A directory opens as a stream on Linux and reads as empty: say what it is.
  if (fs::is_directory(path, ec)) throw ScenarioError(path.string() + ": is a directory, not a scenario file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw ScenarioError(path.string() + ": cannot open scenario file: " + std::strerror(errno));
  std::ostringstream text;
  text << in.rdbuf();
  return ParseScenario(text.str(), path, path.parent_path());
}

fs::path DefaultScenarioPath() {
  if (const char* dir = std::getenv("VESICA_DATA_DIR")) return fs::path(dir) / "scenarios" / "cholecystectomy.toml";
  return fs::path(VESICA_DATA_DIR) / "scenarios" / "cholecystectomy.toml";
}

}  // namespace vesica::app
