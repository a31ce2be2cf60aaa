#include "physics/scene/dissection_scene.h"

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>

#include "physics/bem/tool_contact_load.h"
#include "physics/mesh/barycentric.h"
#include "physics/scene/static_obstacles.h"
#include "physics/tissue/spring_forces.h"

namespace vesica::physics {

// One scalar constraint row: tool point q, tissue point p (barycentric on three nodes of one
// body), direction d. Gap delta = d . (q - p); a force lambda pushes the tissue by -d lambda and
// the tool by +d lambda, so delta' = delta + W lambda with W = d^T C d (constraint_solver.h).
struct DissectionScene::Row {
  bool liver = false;          // body: liver (BEM) or gallbladder (FEM)
  std::array<int, 3> nodes{};  // liver surface vertices or gallbladder volume nodes
  Eigen::Vector3d weights = Eigen::Vector3d::Zero();
  Eigen::Vector3d direction = Eigen::Vector3d::Zero();
  double gap = 0;
  ConstraintKind kind = ConstraintKind::kUnilateral;
  double soft = 0;
  int instrument = 0;                                // -1: a gallbladder node on a static obstacle or the liver
  int grasp_point = -1;                              // index in grasp_.points(), or -1 for a contact row
  int normal_offset = 0;                             // kFriction: its normal row is this many rows before it (< 0)
  double friction = 0;                               // kFriction: Coulomb coefficient
  std::shared_ptr<const BemContactLoad> liver_load;  // a tool on the liver: its footprint (else the point)
  std::shared_ptr<const JawRows> jaw;                // on a jaw's footprint (then not nodes/weights)
};

// A jaw on the gallbladder (a grasp's three rows, or the closed jaws' press): its rows move the
// mean of its footprint's nodes, in series with its subgrid compliance (added between rows
// sharing it).
struct DissectionScene::JawRows {
  std::vector<std::pair<int, double>> points;  // volume node, weight (summing to 1)
  Eigen::Matrix3d subgrid_m_per_N = Eigen::Matrix3d::Zero();
  double rest_offset_m = 0;  // a press: how far the touched point lies out of the mean at rest
  // A grasp: C J^T for its load (grasp_jaw_columns_), one solve instead of a column per node.
  const Eigen::Matrix<double, Eigen::Dynamic, 3>* columns = nullptr;
};

namespace {
using Clock = std::chrono::steady_clock;
double Microseconds(Clock::duration d) { return std::chrono::duration<double, std::micro>(d).count(); }

Eigen::Map<const Vertices> AsVertices(const Eigen::VectorXd& stacked) {
  return {stacked.data(), stacked.size() / 3, 3};
}

void CheckPose(const InstrumentPose& p, int i) {
  const bool finite = std::isfinite(p.yaw_rad) && std::isfinite(p.pitch_rad) && std::isfinite(p.roll_rad) &&
                      std::isfinite(p.insertion_m) && std::isfinite(p.jaw_angle_rad);
  if (!finite || p.insertion_m < 0.0)
    throw std::invalid_argument("DissectionScene::Step: instrument " + std::to_string(i) +
                                " pose is not finite or has negative insertion");
}
}  // namespace

DissectionScene::DissectionScene(std::shared_ptr<const DissectionModel> model)
    : model_(std::move(model)),
      gallbladder_(model_->gallbladder),
      gallbladder_compliance_(model_->gallbladder),
      liver_solver_(*model_->liver),
      tissue_(model_->tissue),
      grasp_(model_->settings.grasp),
      grasp_jaw_(
          model_->gallbladder, model_->gallbladder_boundary,
          GraspJawSettings{model_->settings.grasp_jaw_length_m, model_->settings.grasp_jaw_width_m,
                           model_->settings.grasp_subgrid_patch_radius_m, model_->settings.grasp_subgrid_adopt_steps,
                           model_->settings.grasp_subgrid_ramp_steps}),
      press_subgrid_(model_->gallbladder, grasp_jaw_.boundary(), model_->settings.grasp_subgrid_patch_radius_m,
                     model_->settings.grasp_subgrid_adopt_steps) {
  liver_current_ = model_->liver->rest_surface;
  liver_velocity_ = Vertices::Zero(liver_current_.num_vertices(), 3);
  gallbladder_current_ = model_->gallbladder->rest_mesh;
  obstacle_lambda_.assign(static_cast<size_t>(gallbladder_current_.num_vertices()), {0.0, 0.0, 0.0});
  liver_surface_id_ = caster_.AddSurface(liver_current_);
  gallbladder_surface_id_ = caster_.AddSurface(model_->gallbladder_boundary.surface);
  for (int i = 0; i < 2; ++i)
    tips_[static_cast<size_t>(i)] = model_->instruments[static_cast<size_t>(i)].p_RemoteCentre_W;
  UpdateAttachments(false);
}
DissectionScene::~DissectionScene() = default;

void DissectionScene::UpdateAttachments(bool in_background) {
  const FemModel& m = *model_->gallbladder;
  Eigen::VectorXd k = Eigen::VectorXd::Zero(m.num_dofs()), c = Eigen::VectorXd::Zero(m.num_dofs());
  const SpringMaterial& spring = model_->settings.springs;
  for (const TissueSpring& s : tissue_.springs) {
    if (!s.alive) continue;
    for (int corner = 0; corner < 4; ++corner) {
      const int node = m.rest_mesh.tets(s.gallbladder_tet, corner);
      const double w = std::abs(s.gallbladder_weights[corner]);  // lumped: k w_i on each node (diag(w) >= w w^T)
      k.segment<3>(3 * node).array() += spring.stiffness * w;
      c.segment<3>(3 * node).array() += spring.damping * w;
    }
  }
  AddRetractionStiffness(model_->retraction, k, c);  // the assistant's hold stays while springs go
  for (const int node : outside_load_nodes_)
    k.segment<3>(3 * node).array() +=
        outside_load_stiffness_N_per_m_ / static_cast<double>(outside_load_nodes_.size());  // lumped, as above
  gallbladder_.SetAttachmentStiffness(k, c);
  if (in_background && model_->settings.compliance_adopt_steps > 0) {
    gallbladder_compliance_.BeginAttachments(k, c, gallbladder_.PendingRestFactor());  // one factorisation
    compliance_adopt_step_ = steps_ + model_->settings.compliance_adopt_steps;
  } else {
    gallbladder_compliance_.SetAttachments(k, c);
  }
  attachments_changed_ = false;
  steps_since_compliance_ = 0;
}

void DissectionScene::CutSpring(int index) {
  physics::CutSpring(tissue_, index);
  attachments_changed_ = true;
}

void DissectionScene::SetOutsideLoad(const std::vector<int>& nodes, double stiffness_N_per_m) {
  const int num_nodes = model_->gallbladder->num_nodes();
  for (const int node : nodes)
    if (node < 0 || node >= num_nodes)
      throw std::invalid_argument("DissectionScene::SetOutsideLoad: node " + std::to_string(node) +
                                  " is not a gallbladder node (0.." + std::to_string(num_nodes - 1) + ")");
  if (!std::isfinite(stiffness_N_per_m) || stiffness_N_per_m < 0)
    throw std::invalid_argument("DissectionScene::SetOutsideLoad: stiffness " + std::to_string(stiffness_N_per_m) +
                                " N/m is not a finite value >= 0");
  if (nodes == outside_load_nodes_ && stiffness_N_per_m == outside_load_stiffness_N_per_m_) return;
  // Less stiffness than declared is only sluggish, so it may wait for the background refresh;
  // more (or other nodes) must be in the very next step, or the lagged force overshoots.
  const bool now = nodes != outside_load_nodes_ || stiffness_N_per_m > outside_load_stiffness_N_per_m_;
  outside_load_nodes_ = nodes;
  outside_load_stiffness_N_per_m_ = stiffness_N_per_m;
  if (nodes.empty()) outside_load_force_N_.setZero();
  attachments_changed_ = true;
  if (now) UpdateAttachments(false);
}

void DissectionScene::SetOutsideLoadForce(const Eigen::Vector3d& force_N) {
  if (!force_N.allFinite()) throw std::invalid_argument("DissectionScene::SetOutsideLoadForce: a non-finite force");
  if (outside_load_nodes_.empty())
    throw std::invalid_argument("DissectionScene::SetOutsideLoadForce: no nodes (SetOutsideLoad first)");
  outside_load_force_N_ = force_N;
}

Vertices DissectionScene::gallbladder_surface_positions() const {
  const Eigen::VectorXi& map = model_->gallbladder_boundary.surface_to_volume;
  Vertices out(map.size(), 3);
  for (Eigen::Index i = 0; i < map.size(); ++i) out.row(i) = gallbladder_current_.vertices.row(map[i]);
  return out;
}

Vertices DissectionScene::membrane_points() const {
  Vertices out(2 * static_cast<Eigen::Index>(tissue_.springs.size()), 3);
  for (size_t s = 0; s < tissue_.springs.size(); ++s) {
    const TissueSpring& spring = tissue_.springs[s];
    out.row(2 * static_cast<Eigen::Index>(s)) =
        GallbladderEnd(spring, gallbladder_current_.vertices, gallbladder_current_.tets).transpose();
    out.row(2 * static_cast<Eigen::Index>(s) + 1) =
        LiverEnd(spring, liver_current_.vertices, liver_current_.triangles).transpose();
  }
  return out;
}

double DissectionScene::Energy() const {
  double springs = 0;
  for (const TissueSpring& s : tissue_.springs) {
    if (!s.alive) continue;
    const double stretch = (LiverEnd(s, liver_current_.vertices, liver_current_.triangles) -
                            GallbladderEnd(s, gallbladder_current_.vertices, gallbladder_current_.tets))
                               .norm() -
                           s.rest_length;
    springs += 0.5 * model_->settings.springs.stiffness * stretch * stretch;
  }
  if (!model_->retraction.empty()) springs += RetractionEnergy(model_->retraction, gallbladder_current_.vertices);
  return gallbladder_.KineticEnergy() + gallbladder_.ElasticEnergy() + springs;
}

// d_a^T C(p_a, p_b) d_b for two rows on the same body; zero across bodies (they only interact
// through the springs, which the step treats outside the constraint solve).
Eigen::Matrix3d DissectionScene::BlockCompliance(const Row& a, const Row& b) {
  Eigen::Matrix3d c = Eigen::Matrix3d::Zero();
  if (a.liver != b.liver) return c;
  if (a.liver && a.liver_load && b.liver_load)
    return ContactLoadCompliance(*model_->liver, *a.liver_load, *b.liver_load);
  if (a.jaw || b.jaw) {  // a jaw's footprint: every node of it
    std::vector<std::pair<int, double>> pa, pb;
    GallbladderPoints(a, pa);
    GallbladderPoints(b, pb);
    // With the load's columns X = C J^T: C(p_a, jaw) = sum_a w_a X(a), C(jaw, p_b) = its transpose.
    if (b.jaw && b.jaw->columns) {
      for (const auto& [node_a, wa] : pa) c += wa * b.jaw->columns->block<3, 3>(3 * node_a, 0);
      return c;
    }
    if (a.jaw && a.jaw->columns) {
      for (const auto& [node_b, wb] : pb) c += wb * a.jaw->columns->block<3, 3>(3 * node_b, 0).transpose();
      return c;
    }
    for (const auto& [node_b, wb] : pb) {
      const auto& columns = gallbladder_compliance_.NodeColumns(node_b);
      for (const auto& [node_a, wa] : pa) c += wa * wb * columns.block<3, 3>(3 * node_a, 0);
    }
    return c;
  }
  for (int j = 0; j < 3; ++j) {
    if (b.weights[j] == 0.0) continue;
    if (a.liver) {
      const BemModel& liver = *model_->liver;
      const int fj = liver.layout.free_index(b.nodes[static_cast<size_t>(j)]);
      if (fj < 0) continue;  // a force on the fixed region moves nothing
      for (int i = 0; i < 3; ++i) {
        const int node_i = a.nodes[static_cast<size_t>(i)];
        if (a.weights[i] == 0.0 || liver.layout.free_index(node_i) < 0) continue;
        c += a.weights[i] * b.weights[j] / liver.lumped_area_m2(b.nodes[static_cast<size_t>(j)]) *
             liver.greens.block<3, 3>(3 * node_i, 3 * fj);
      }
    } else {
      const auto& columns = gallbladder_compliance_.NodeColumns(b.nodes[static_cast<size_t>(j)]);
      for (int i = 0; i < 3; ++i)
        if (a.weights[i] != 0.0)
          c += a.weights[i] * b.weights[j] * columns.block<3, 3>(3 * a.nodes[static_cast<size_t>(i)], 0);
    }
  }
  return c;
}

std::shared_ptr<const DissectionScene::JawRows> DissectionScene::PressingJaw(const SurfaceHit& hit,
                                                                             const Eigen::Vector3d& shaft) {
  const DissectionSettings& s = model_->settings;
  const TriangleMesh& rest = model_->gallbladder_boundary.surface;
  const std::optional<RectangularFootprint> at =
      JawFootprintAt(rest, hit.triangle, hit.weights, shaft, s.grasp_jaw_length_m, s.grasp_jaw_width_m);
  if (!at) return nullptr;
  FootprintWeights footprint;
  try {
    footprint = ComputeFootprintWeights(model_->gallbladder_boundary, *at);
  } catch (const std::invalid_argument&) {
    return nullptr;  // no surface under the jaw: the touched point presses
  }
  auto jaw = std::make_shared<JawRows>();
  for (size_t i = 0; i < footprint.nodes.size(); ++i)
    jaw->points.emplace_back(footprint.nodes[i],
                             footprint.moments(static_cast<Eigen::Index>(i), 0) / footprint.area_m2);
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const auto& [node, w] : jaw->points) mean += w * model_->gallbladder->rest_mesh.vertices.row(node).transpose();
  jaw->rest_offset_m = at->normal.dot(at->centre_m - mean);
  int corner = 0;
  hit.weights.maxCoeff(&corner);
  const double normal = press_subgrid_.At(rest.triangles(hit.triangle, corner), *at, steps_);
  jaw->subgrid_m_per_N = normal * hit.normal * hit.normal.transpose();
  return jaw;
}

void DissectionScene::GallbladderPoints(const Row& r, std::vector<std::pair<int, double>>& out) const {
  out.clear();
  if (r.jaw) {
    out = r.jaw->points;
    return;
  }
  for (int j = 0; j < 3; ++j)
    if (r.weights[j] != 0.0) out.emplace_back(r.nodes[static_cast<size_t>(j)], r.weights[j]);
}

// The obstacle rows are grouped by node (a contact row, then its friction rows), each on one
// gallbladder node with weight 1: rows g and h of nodes p and q couple through the 3x3 block
// C(p, q) of the rest compliance, so W's obstacle part is D_p^T C(p, q) D_q per pair of nodes
// (D: the group's row directions), one block lookup and two small products per pair instead of
// one per pair of rows.
void DissectionScene::AddObstacleDelassus(const std::vector<Row>& rows, Eigen::Index first,
                                          ConstraintProblem& problem) {
  const Eigen::Index m = static_cast<Eigen::Index>(rows.size());
  struct Group {
    int node;
    Eigen::Index first, count;
    Eigen::Matrix3d directions;  // columns: the rows' directions
  };
  std::vector<Group> groups;
  for (Eigen::Index a = first; a < m; ++a) {
    const Row& r = rows[static_cast<size_t>(a)];
    if (groups.empty() || groups.back().node != r.nodes[0])
      groups.push_back({r.nodes[0], a, 0, Eigen::Matrix3d::Zero()});
    Group& g = groups.back();
    g.directions.col(g.count++) = r.direction;
  }
  // Each pair once, mirrored (measured with callgrind: computing both sides instead costs 1.6x).
  for (size_t h = 0; h < groups.size(); ++h) {
    const Group& gh = groups[h];
    const auto& columns = gallbladder_compliance_.NodeColumns(gh.node);
    for (size_t g = 0; g <= h; ++g) {
      const Group& gg = groups[g];
      const Eigen::Matrix3d c = columns.block<3, 3>(3 * gg.node, 0);
      const Eigen::Matrix3d cd = c * gh.directions;
      const Eigen::Matrix3d w = gg.directions.transpose() * cd;
      for (Eigen::Index j = 0; j < gh.count; ++j)
        for (Eigen::Index i = 0; i < gg.count; ++i) {
          problem.delassus(gg.first + i, gh.first + j) = w(i, j);
          problem.delassus(gh.first + j, gg.first + i) = w(i, j);
        }
    }
  }
}

std::vector<DissectionScene::Row> DissectionScene::ObstacleRows(const Vertices& gb_start, const Vertices& gb_free,
                                                                const Vertices& liver_free) const {
  const DissectionSettings& s = model_->settings;
  std::vector<Row> rows;
  if (model_->obstacles.empty() && model_->liver_proximity.empty()) return rows;
  if (s.static_contact_only_when_free && !gallbladder_free()) return rows;
  const Eigen::VectorXi& boundary_nodes = model_->gallbladder_boundary.surface_to_volume;
  SurfaceProximityGrid::Frame liver_frame;
  if (!model_->liver_proximity.empty()) liver_frame = model_->liver_proximity.MakeFrame(liver_free);
  for (Eigen::Index k = 0; k < boundary_nodes.size(); ++k) {
    const int node = boundary_nodes[k];
    const Eigen::Vector3d p = gb_free.row(node).transpose();
    std::optional<ObstacleProximity> near =
        NearestObstacle(model_->obstacles, p, s.obstacle_margin_m, s.obstacle_max_depth_m);
    if (!model_->liver_proximity.empty()) {
      const double within = std::max(s.obstacle_margin_m, s.obstacle_max_depth_m);
      const std::optional<SurfaceProximity> liver = model_->liver_proximity.Nearest(p, liver_frame, within);
      if (liver && liver->signed_distance_m <= s.obstacle_margin_m &&
          liver->signed_distance_m > -s.obstacle_max_depth_m &&
          (!near || liver->signed_distance_m < near->signed_distance_m))
        near = ObstacleProximity{liver->p_Surface_W, liver->normal_W, liver->signed_distance_m};
    }
    if (!near) continue;
    // The obstacle is the row's "tool": delta = d . (q - p) with d = -n is the node's signed
    // distance, and lambda >= 0 pushes the node along +n, out of the obstacle.
    Row r;
    r.liver = false;
    r.nodes = {node, node, node};
    r.weights = Eigen::Vector3d::UnitX();
    r.direction = -near->normal_W;
    r.gap = std::max(near->signed_distance_m, -s.max_correction_per_step_m);
    r.kind = ConstraintKind::kUnilateral;
    r.soft = s.obstacle_compliance_m_per_N;
    r.instrument = -1;
    rows.push_back(r);
    if (near->signed_distance_m >= 0.0 || s.obstacle_friction == 0.0) continue;
    // Pressed (the free step took it in): two tangential rows hold it where it was at the step's
    // start, each up to mu times the normal force (Coulomb's pyramid), so it sticks or slides.
    const Eigen::Vector3d t1 = near->normal_W.unitOrthogonal();
    const Eigen::Vector3d t2 = near->normal_W.cross(t1);
    const Eigen::Vector3d slip_back = gb_start.row(node).transpose() - p;
    for (int axis = 0; axis < 2; ++axis) {
      Row f = r;
      f.direction = axis == 0 ? t1 : t2;
      f.gap = f.direction.dot(slip_back);
      f.kind = ConstraintKind::kFriction;
      f.normal_offset = -1 - axis;
      f.friction = s.obstacle_friction;
      rows.push_back(f);
    }
  }
  return rows;
}

DissectionStepReport DissectionScene::Step(const std::array<InstrumentPose, 2>& poses) {
  for (int i = 0; i < 2; ++i) CheckPose(poses[static_cast<size_t>(i)], i);
  const DissectionSettings& s = model_->settings;
  const double h = s.time_step_s;
  const FemModel& gb_model = *model_->gallbladder;
  const BemModel& liver = *model_->liver;
  const TetBoundary& boundary = model_->gallbladder_boundary;
  DissectionStepReport report;
  const Clock::time_point start = Clock::now();
  Clock::time_point last = start;
  auto lap = [&](double& slot) {
    const Clock::time_point now = Clock::now();
    slot = Microseconds(now - last);
    last = now;
  };

  // 1. Instrument poses -> tool points.
  std::array<Eigen::Vector3d, 2> dirs;
  for (size_t i = 0; i < 2; ++i) {
    const InstrumentMount& mount = model_->instruments[i];
    tips_[i] = TipPosition(mount.p_RemoteCentre_W, mount.reference_direction_W, poses[i]);
    dirs[i] = ShaftDirection(mount.reference_direction_W, poses[i]);
  }

  // 2. Spring forces at the current state.
  // Springs cut: their stiffness leaves the implicit system now and the constraint compliance
  // a few steps later, when its factorisation on the worker thread is adopted.
  if (compliance_adopt_step_ >= 0 && steps_ >= compliance_adopt_step_) {
    gallbladder_compliance_.AdoptAttachments();
    compliance_adopt_step_ = -1;
  }
  if (attachments_changed_ && steps_since_compliance_ >= s.compliance_refresh_steps) UpdateAttachments(true);
  ++steps_since_compliance_;
  const TissueNodalForces spring_forces =
      ComputeTissueForces(tissue_, gallbladder_current_, AsVertices(gallbladder_.state().velocity_m_per_s),
                          liver_current_, liver_velocity_, s.springs);
  lap(report.times.springs_us);

  // 3. Free motion: the gallbladder's implicit step, the liver's quasi-static response.
  Eigen::VectorXd f_ext = AsStackedVector(spring_forces.gallbladder);
  if (!s.gravity_m_per_s2.isZero()) f_ext += gb_model.GravityForces(s.gravity_m_per_s2);
  for (const int node : outside_load_nodes_)
    f_ext.segment<3>(3 * node) += outside_load_force_N_ / static_cast<double>(outside_load_nodes_.size());
  if (!model_->retraction.empty())
    AddRetractionForces(model_->retraction, gallbladder_current_.vertices, gallbladder_.state().velocity_m_per_s,
                        f_ext);
  gallbladder_.SetExternalForces(f_ext);
  const StepReport fem = gallbladder_.Step();
  report.gallbladder_accepted = fem.accepted;
  report.rejection_reason = fem.rejection_reason;
  report.gallbladder_solver_iterations = fem.solver_iterations;
  report.gallbladder_relative_residual = fem.relative_residual;
  Vertices gb_free = gallbladder_.CurrentPositions();
  lap(report.times.gallbladder_us);

  std::vector<int> loaded;
  std::vector<Eigen::Vector3d> loads;
  for (int v = 0; v < liver.num_nodes(); ++v) {
    if (liver.layout.free_index(v) < 0) continue;
    const Eigen::Vector3d f = spring_forces.liver.row(v).transpose();
    if (f.isZero()) continue;
    loaded.push_back(v);
    loads.push_back(f / liver.lumped_area_m2(v));
  }
  Vertices tractions(static_cast<Eigen::Index>(loaded.size()), 3);
  for (size_t k = 0; k < loaded.size(); ++k) tractions.row(static_cast<Eigen::Index>(k)) = loads[k].transpose();
  liver_solver_.SetAppliedTractions(loaded, tractions);
  liver_solver_.Solve(Vertices(0, 3), liver_solution_);
  Vertices liver_free = liver.rest_surface.vertices + liver_solution_.displacement_m;
  lap(report.times.liver_us);

  // 4. Ray collision of each tool against the free surfaces.
  Vertices gb_surface_free(boundary.surface_to_volume.size(), 3);
  for (Eigen::Index i = 0; i < gb_surface_free.rows(); ++i)
    gb_surface_free.row(i) = gb_free.row(boundary.surface_to_volume[i]);
  caster_.UpdateVertices(liver_surface_id_, liver_free);
  caster_.UpdateVertices(gallbladder_surface_id_, gb_surface_free);
  std::array<std::optional<SurfaceHit>, 2> hits;
  std::array<double, 2> hit_gap{0, 0};
  for (size_t i = 0; i < 2; ++i) {
    const ToolSegment ray{model_->instruments[i].p_RemoteCentre_W, tips_[i] + s.contact_margin_m * dirs[i]};
    std::optional<SurfaceHit> hit = caster_.FirstHit(ray);
    if (hit && !hit->from_inside) {
      hits[i] = hit;
      hit_gap[i] = hit->normal.dot(tips_[i] - hit->point);
    }
  }
  const std::vector<Row> obstacle_rows = ObstacleRows(gallbladder_current_.vertices, gb_free, liver_free);
  lap(report.times.collision_us);

  // 5. Grasp / slip / release (the left instrument, when it is a grasper).
  const bool has_grasper = model_->instruments[0].role == InstrumentRole::kGrasper;
  auto gb_point = [&](int triangle, const Eigen::Vector3d& w, const Vertices& x) {
    Eigen::Vector3d p = Eigen::Vector3d::Zero();
    for (int k = 0; k < 3; ++k) p += w[k] * x.row(boundary.surface.triangles(triangle, k)).transpose();
    return p;
  };
  if (has_grasper) {
    GraspInput in;
    in.jaw_angle = poses[0].jaw_angle_rad;
    in.jaw_position = tips_[0];
    if (hits[0] && hits[0]->surface == gallbladder_surface_id_ && hit_gap[0] <= s.grasp_reach_m)
      in.hits.push_back(*hits[0]);
    if (grasp_.state() == GraspStateMachine::State::kHolding) {
      // A jaw holds its footprint's mean, which lags the jaw by the subgrid compliance times the
      // force: the tissue's give around the jaw, not a slip. So the jaw's held point is the mean
      // less that lag (for every grasped point).
      std::optional<Eigen::Vector3d> jaw_held;
      if (grasp_jaw_.holding()) {
        Eigen::Vector3d mean = Eigen::Vector3d::Zero();
        for (size_t i = 0; i < grasp_jaw_.nodes().size(); ++i)
          mean += grasp_jaw_.weights()[i] * gb_free.row(grasp_jaw_.nodes()[i]).transpose();
        jaw_held = mean - grasp_jaw_.SubgridAt(steps_) * frames_[0].f_Tool_W;
      }
      for (size_t k = 0; k < grasp_.points().size(); ++k) {
        in.grasped_positions.push_back(
            jaw_held ? *jaw_held : gb_point(grasp_.points()[k].triangle, grasp_.points()[k].weights, gb_surface_free));
        in.constraint_forces.push_back(k < grasp_point_forces_.size() ? grasp_point_forces_[k] : 0.0);
      }
    }
    report.grasp = grasp_.Update(in);
  }
  const bool holding = has_grasper && grasp_.state() == GraspStateMachine::State::kHolding;
  if (!holding && grasp_jaw_.holding()) grasp_jaw_.Release();
  if (holding && report.grasp.grasped && s.grasp_holds_jaw_footprint &&
      grasp_jaw_.Take(grasp_.points().front().triangle, grasp_.points().front().weights, dirs[0], steps_))
    grasp_jaw_take_step_ = steps_;
  lap(report.times.grasp_us);

  // 6. Constraint rows and the solve (W + W_soft) lambda + delta = 0.
  std::vector<Row> rows;
  auto tissue_row = [&](bool on_liver, int triangle, const Eigen::Vector3d& w) {
    Row r;
    r.liver = on_liver;
    r.weights = w;
    for (int k = 0; k < 3; ++k)
      r.nodes[static_cast<size_t>(k)] = on_liver ? liver.rest_surface.triangles(triangle, k)
                                                 : boundary.surface_to_volume[boundary.surface.triangles(triangle, k)];
    return r;
  };
  if (holding && grasp_jaw_.holding()) {
    // The jaw holds its footprint's mean: one row per axis for every grasped point together.
    auto jaw = std::make_shared<JawRows>();
    for (size_t i = 0; i < grasp_jaw_.nodes().size(); ++i)
      jaw->points.emplace_back(grasp_jaw_.nodes()[i], grasp_jaw_.weights()[i]);
    jaw->subgrid_m_per_N = grasp_jaw_.SubgridAt(steps_);
    if (grasp_jaw_columns_take_ != grasp_jaw_take_step_ ||
        grasp_jaw_columns_factorization_ != gallbladder_compliance_.factorizations()) {
      grasp_jaw_columns_ = gallbladder_compliance_.LoadColumns(jaw->points);
      grasp_jaw_columns_take_ = grasp_jaw_take_step_;
      grasp_jaw_columns_factorization_ = gallbladder_compliance_.factorizations();
    }
    jaw->columns = &grasp_jaw_columns_;
    Eigen::Vector3d p = Eigen::Vector3d::Zero();
    for (const auto& [node, w] : jaw->points) p += w * gb_free.row(node).transpose();
    for (int axis = 0; axis < 3; ++axis) {
      Row r;
      r.liver = false;
      r.jaw = jaw;
      r.direction = Eigen::Vector3d::Unit(axis);
      r.gap = r.direction.dot(tips_[0] - p);  // not clamped: that would cap the hold force
      r.kind = ConstraintKind::kBilateral;
      r.soft = s.grasp_compliance_m_per_N;
      r.instrument = 0;
      r.grasp_point = 0;
      rows.push_back(r);
    }
  } else if (holding) {
    for (size_t k = 0; k < grasp_.points().size(); ++k) {
      const GraspPoint& g = grasp_.points()[k];
      const Eigen::Vector3d p = gb_point(g.triangle, g.weights, gb_surface_free);
      for (int axis = 0; axis < 3; ++axis) {
        Row r = tissue_row(false, g.triangle, g.weights);
        r.direction = Eigen::Vector3d::Unit(axis);
        r.gap = r.direction.dot(tips_[0] - p);  // not clamped: that would cap the hold force
        r.kind = ConstraintKind::kBilateral;
        r.soft = s.grasp_compliance_m_per_N;
        r.instrument = 0;
        r.grasp_point = static_cast<int>(k);
        rows.push_back(r);
      }
    }
  }
  for (size_t i = 0; i < 2; ++i) {
    if (!hits[i] || (i == 0 && holding)) continue;
    Row r = tissue_row(hits[i]->surface == liver_surface_id_, hits[i]->triangle, hits[i]->weights);
    const double footprint_m = model_->instruments[i].role == InstrumentRole::kGrasper
                                   ? s.grasper_liver_footprint_radius_m
                                   : s.hook_liver_footprint_radius_m;
    if (r.liver && footprint_m > 0)
      r.liver_load = std::make_shared<const BemContactLoad>(
          MakeToolContactLoad(liver, hits[i]->triangle, hits[i]->weights, hits[i]->normal, footprint_m));
    r.direction = hits[i]->normal;
    if (!r.liver && i == 0 && model_->instruments[i].role == InstrumentRole::kGrasper &&
        s.grasper_presses_jaw_footprint && poses[i].jaw_angle_rad <= s.grasp.close_angle)
      r.jaw = PressingJaw(*hits[i], dirs[i]);
    r.gap = std::max(hit_gap[i], -s.max_correction_per_step_m);
    if (r.jaw) {
      // The jaw presses its footprint's mean (where its rows' compliance acts), measured from
      // where the mean lies under the touched point at rest. The series part of the gap the
      // last step's force keeps open is not a penetration to be limited.
      Eigen::Vector3d mean = Eigen::Vector3d::Zero();
      for (const auto& [node, w] : r.jaw->points) mean += w * gb_free.row(node).transpose();
      const double series =
          r.direction.dot(r.jaw->subgrid_m_per_N * r.direction) * std::max(0.0, frames_[i].f_Tool_W.dot(r.direction));
      r.gap = std::max(r.direction.dot(tips_[i] - mean) - r.jaw->rest_offset_m, -s.max_correction_per_step_m - series);
    }
    r.kind = ConstraintKind::kUnilateral;
    r.soft = s.contact_compliance_m_per_N;
    r.instrument = static_cast<int>(i);
    rows.push_back(r);
  }
  rows.insert(rows.end(), obstacle_rows.begin(), obstacle_rows.end());
  const Eigen::Index m = static_cast<Eigen::Index>(rows.size());
  const Eigen::Index first_obstacle = m - static_cast<Eigen::Index>(obstacle_rows.size());
  ConstraintProblem problem;
  problem.delassus.setZero(m, m);
  problem.soft_compliance.resize(m);
  problem.gap.resize(m);
  for (Eigen::Index a = 0; a < m; ++a) {
    const Row& ra = rows[static_cast<size_t>(a)];
    problem.soft_compliance[a] = ra.soft;
    problem.gap[a] = ra.gap;
    problem.kinds.push_back(ra.kind);
    problem.normal_row.push_back(ra.kind == ConstraintKind::kFriction ? static_cast<int>(a) + ra.normal_offset : -1);
    problem.friction_coefficient.push_back(ra.friction);
  }
  // The obstacle rows among themselves: AddObstacleDelassus, node by node.
  for (Eigen::Index a = 0; a < first_obstacle; ++a) {
    const Row& ra = rows[static_cast<size_t>(a)];
    // An obstacle's contact and friction rows share their node: consecutive rows b on the same
    // points as the one before reuse its block (the same numbers, computed once).
    const Row* block_of = nullptr;
    Eigen::Matrix3d block = Eigen::Matrix3d::Zero();
    for (Eigen::Index b = a; b < m; ++b) {
      const Row& rb = rows[static_cast<size_t>(b)];
      if (block_of == nullptr || block_of->liver != rb.liver || block_of->nodes != rb.nodes ||
          block_of->weights != rb.weights || block_of->jaw != rb.jaw) {
        block = BlockCompliance(ra, rb);
        block_of = &rb;
      }
      double w = ra.direction.dot(block * rb.direction);
      if (ra.jaw && ra.jaw == rb.jaw) w += ra.direction.dot(ra.jaw->subgrid_m_per_N * rb.direction);  // in series
      problem.delassus(a, b) = w;
      problem.delassus(b, a) = w;
    }
  }
  if (first_obstacle < m) AddObstacleDelassus(rows, first_obstacle, problem);
  report.constraint_rows = static_cast<int>(m);
  // With the freed gallbladder's resting rows (hundreds where a flat face lies on an organ) a
  // sweep costs m^2: a capped number of sweeps keeps the step bounded; what one step leaves
  // unresolved of a resting contact shows as a gap the next step's rows close.
  ConstraintSolverSettings solver;
  if (!obstacle_rows.empty()) {
    // Only after the freeing (earlier steps keep their bits): warm-started from the last step's
    // obstacle forces, stopped when a sweep changes no row by more than obstacle_tolerance_m.
    solver.max_iterations = s.obstacle_max_sweeps;
    solver.fast_large_problems = true;
    solver.change_tolerance_m = s.obstacle_tolerance_m;
    problem.initial_lambda = Eigen::VectorXd::Zero(m);
    for (Eigen::Index a = first_obstacle; a < m; ++a) {
      const Row& r = rows[static_cast<size_t>(a)];
      const int slot = r.kind == ConstraintKind::kFriction ? -r.normal_offset : 0;
      problem.initial_lambda[a] = obstacle_lambda_[static_cast<size_t>(r.nodes[0])][static_cast<size_t>(slot)];
    }
  }
  report.constraints = SolveConstraints(problem, solver);
  const Eigen::VectorXd& lambda = report.constraints.lambda;
  for (int node : obstacle_lambda_nodes_) obstacle_lambda_[static_cast<size_t>(node)] = {0.0, 0.0, 0.0};
  obstacle_lambda_nodes_.clear();
  for (Eigen::Index a = first_obstacle; a < m; ++a) {
    const Row& r = rows[static_cast<size_t>(a)];
    const int slot = r.kind == ConstraintKind::kFriction ? -r.normal_offset : 0;
    if (slot == 0) obstacle_lambda_nodes_.push_back(r.nodes[0]);
    obstacle_lambda_[static_cast<size_t>(r.nodes[0])][static_cast<size_t>(slot)] = lambda[a];
  }
  lap(report.times.constraints_us);

  // 7. Correction: each body moves by C J^T lambda (force -d lambda on the tissue point).
  Eigen::VectorXd du_gb = Eigen::VectorXd::Zero(gb_model.num_dofs());
  Eigen::VectorXd du_liver = Eigen::VectorXd::Zero(3 * liver.num_nodes());
  for (Eigen::Index a = 0; a < first_obstacle; ++a) {
    if (lambda[a] == 0.0) continue;
    const Row& r = rows[static_cast<size_t>(a)];
    const Eigen::Vector3d force = -r.direction * lambda[a];
    if (r.liver_load) {
      AddContactLoadResponse(liver, *r.liver_load, force, du_liver);
      continue;
    }
    if (r.jaw && r.jaw->columns) {
      du_gb.noalias() += *r.jaw->columns * force;
      continue;
    }
    if (r.jaw) {
      for (const auto& [node, w] : r.jaw->points)
        du_gb.noalias() += gallbladder_compliance_.NodeColumns(node) * (w * force);
      continue;
    }
    for (int j = 0; j < 3; ++j) {
      const int node = r.nodes[static_cast<size_t>(j)];
      if (r.weights[j] == 0.0) continue;
      if (r.liver) {
        const int fj = liver.layout.free_index(node);
        if (fj >= 0)
          du_liver.noalias() +=
              liver.greens.middleCols<3>(3 * fj) * (r.weights[j] * force / liver.lumped_area_m2(node));
      } else {
        du_gb.noalias() += gallbladder_compliance_.NodeColumns(node) * (r.weights[j] * force);
      }
    }
  }
  // An obstacle's node takes its contact and friction rows' forces summed: one column block each.
  for (Eigen::Index a = first_obstacle; a < m;) {
    const int node = rows[static_cast<size_t>(a)].nodes[0];
    Eigen::Vector3d force = Eigen::Vector3d::Zero();
    for (; a < m && rows[static_cast<size_t>(a)].nodes[0] == node; ++a)
      force -= rows[static_cast<size_t>(a)].direction * lambda[a];
    if (!force.isZero()) du_gb.noalias() += gallbladder_compliance_.NodeColumns(node) * force;
  }
  if (!du_gb.isZero()) {
    gallbladder_.SetState(gallbladder_.state().displacement_m + du_gb,
                          gallbladder_.state().velocity_m_per_s + du_gb / h);
  }
  gallbladder_current_.vertices = gallbladder_.CurrentPositions();
  Vertices liver_new = liver_free;
  for (int v = 0; v < liver.num_nodes(); ++v)
    if (liver.layout.free_index(v) >= 0) liver_new.row(v) += du_liver.segment<3>(3 * v).transpose();
  // liver_velocity_ stays zero: the liver is quasi-static, and feeding its step-to-step jumps back
  // through the springs' damping makes an explicit loop that can diverge (measured on the default scene).
  (void)0;
  liver_current_.vertices = std::move(liver_new);
  lap(report.times.correction_us);

  // 8. Tool forces, grasp point forces, haptic frames and touches.
  grasp_point_forces_.assign(holding ? grasp_.points().size() : 0, 0.0);
  std::array<std::vector<Eigen::Index>, 2> active;
  for (Eigen::Index a = 0; a < m; ++a) {
    const Row& r = rows[static_cast<size_t>(a)];
    if (r.instrument < 0) {
      if (r.kind == ConstraintKind::kUnilateral && lambda[a] > 0.0) ++report.obstacle_contacts;
      continue;
    }
    report.tool_force_N[static_cast<size_t>(r.instrument)] += r.direction * lambda[a];
    if (r.grasp_point >= 0) {
      double& f = grasp_point_forces_[static_cast<size_t>(r.grasp_point)];
      f = std::hypot(f, lambda[a]);
    }
    if (r.jaw && r.kind == ConstraintKind::kBilateral)  // the jaw's force holds every grasped point
      for (size_t k = 1; k < grasp_point_forces_.size(); ++k) grasp_point_forces_[k] = grasp_point_forces_[0];
    if (lambda[a] > 0.0 || r.kind == ConstraintKind::kBilateral) active[static_cast<size_t>(r.instrument)].push_back(a);
  }
  // W + W_soft of the tools' rows (the obstacle rows, hundreds after the freeing, are not needed).
  const Eigen::MatrixXd system = problem.delassus.topLeftCorner(first_obstacle, first_obstacle) +
                                 Eigen::MatrixXd(problem.soft_compliance.head(first_obstacle).asDiagonal());
  for (size_t i = 0; i < 2; ++i) {
    HapticContactFrame frame;
    frame.time_s = static_cast<double>(steps_ + 1) * h;
    frame.p_Tool_W = tips_[i];
    frame.f_Tool_W = report.tool_force_N[i];
    frame.unilateral = !(i == 0 && holding);
    frame.active = !active[i].empty();
    if (frame.active) {
      // Moving this tool by dp changes its rows' gaps by G^T dp: dlambda = A^-1 G^T dp and the
      // force on the tool by G dlambda, so its stiffness is G A^-1 G^T (the other tool held still).
      const Eigen::Index k = static_cast<Eigen::Index>(active[i].size());
      Eigen::MatrixXd a_sub(k, k), g(3, k);
      for (Eigen::Index p = 0; p < k; ++p) {
        g.col(p) = rows[static_cast<size_t>(active[i][static_cast<size_t>(p)])].direction;
        for (Eigen::Index q = 0; q < k; ++q)
          a_sub(p, q) = system(active[i][static_cast<size_t>(p)], active[i][static_cast<size_t>(q)]);
      }
      frame.stiffness_N_per_m = g * a_sub.ldlt().solve(g.transpose());
      if (frame.unilateral) frame.normal_W = hits[i]->normal;
    }
    frames_[i] = frame;

    ToolTouch& touch = report.touches[i];
    touch.p_Tip_W = tips_[i];
    if (hits[i]) {
      // The gap after the correction: the solved rows close it exactly; others keep their own.
      double gap = hit_gap[i];
      for (Eigen::Index a = 0; a < first_obstacle; ++a)
        if (rows[static_cast<size_t>(a)].instrument == static_cast<int>(i) &&
            rows[static_cast<size_t>(a)].grasp_point < 0)
          gap = first_obstacle == m  // no obstacle rows: as the recordings were made, bit for bit
                    ? (system.row(a) * lambda)(0) + problem.gap[a]
                    : (system.row(a) * lambda.head(first_obstacle))(0) +
                          problem.delassus.row(a).tail(m - first_obstacle).dot(lambda.tail(m - first_obstacle)) +
                          problem.gap[a];
      touch.gap_m = gap;
      if (gap <= s.touch_tolerance_m) {
        touch.surface = hits[i]->surface == liver_surface_id_ ? TouchedSurface::kLiver : TouchedSurface::kGallbladder;
        touch.triangle = hits[i]->triangle;
        touch.weights = hits[i]->weights;
      }
    }
  }
  // Membrane elements around the hook tip (the membrane has no mechanics of its own: it burns).
  {
    const Vertices points = membrane_points();
    const TissueMembrane& membrane = tissue_.membrane;
    for (size_t i = 0; i < 2; ++i) {
      if (model_->instruments[i].role != InstrumentRole::kCauteryHook) continue;
      for (Eigen::Index e = 0; e < membrane.triangles.rows(); ++e) {
        const TrianglePoint cp = ClosestPointOnTriangle(tips_[i], points.row(membrane.triangles(e, 0)).transpose(),
                                                        points.row(membrane.triangles(e, 1)).transpose(),
                                                        points.row(membrane.triangles(e, 2)).transpose());
        if ((cp.point - tips_[i]).norm() <= s.membrane_touch_radius_m)
          report.touches[i].membrane_elements.push_back(static_cast<int>(e));
      }
    }
  }
  ++steps_;
  // k h, not a running sum: a recording's frame times then equal a replay's sample times
  // exactly, so replaying a closed-loop run reproduces it bit for bit.
  time_s_ = static_cast<double>(steps_) * h;
  report.times.total_us = Microseconds(Clock::now() - start);
  return report;
}

}  // namespace vesica::physics
