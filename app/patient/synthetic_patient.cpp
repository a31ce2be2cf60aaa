#include "app/patient/synthetic_patient.h"

#include <Eigen/LU>
#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "physics/patient/patient_labels.h"

namespace vesica::app::patient {
namespace label = physics::patient_label;
namespace {

constexpr double kPi = std::numbers::pi;

// Field of view: 36 x 26 x 42 cm, from below the costal margin to above rib 1.
constexpr double kHalfX = 0.18, kHalfY = 0.13, kHalfZ = 0.21;
// Body: an elliptic cylinder 33 x 24 cm (chest breadth and depth of an adult man; ANSUR II).
constexpr double kBodyA = 0.165, kBodyB = 0.12;
constexpr double kSkin = 0.002, kFat = 0.015, kAbdominalMuscle = 0.012;
constexpr double kCageCentreY = 0.005;

// The ribs: head height (one thoracic vertebra and disc, 23 mm, apart), the cage's half-breadth A
// and half-depth B at that rib, and how far its front end drops below its head.
struct RibShape {
  double a, b, drop, theta_bone, theta_end;
};
constexpr double RibHead(int n) { return 0.185 - 0.023 * (n - 1); }
const std::array<RibShape, 12>& Ribs() {
  static const std::array<RibShape, 12> ribs = [] {
    const double a[] = {0.055, 0.080, 0.100, 0.115, 0.125, 0.130, 0.135, 0.135, 0.133, 0.128, 0.120, 0.110};
    const double b[] = {0.050, 0.065, 0.075, 0.085, 0.090, 0.095, 0.095, 0.095, 0.095, 0.092, 0.088, 0.085};
    const double drop[] = {0.030, 0.045, 0.060, 0.070, 0.080, 0.085, 0.090, 0.090, 0.085, 0.080, 0.060, 0.050};
    std::array<RibShape, 12> r{};
    for (int n = 1; n <= 12; ++n) {
      RibShape& s = r[static_cast<std::size_t>(n - 1)];
      s = {a[n - 1], b[n - 1], drop[n - 1], 0.0, 0.0};
      if (n <= 7) {  // true ribs: cartilage to the sternum's edge
        s.theta_bone = 0.80 * kPi;
        s.theta_end = kPi - std::asin(0.016 / s.a);
      } else if (n <= 10) {  // false ribs: cartilage to the costal margin
        s.theta_bone = 0.70 * kPi;
        s.theta_end = 0.85 * kPi;
      } else {  // floating ribs: a cartilage tip
        s.theta_bone = (n == 11 ? 0.55 : 0.45) * kPi;
        s.theta_end = s.theta_bone + 0.05 * kPi;
      }
    }
    return r;
  }();
  return ribs;
}

Eigen::Vector3d RibPoint(int n, bool left, double theta) {
  const RibShape& s = Ribs()[static_cast<std::size_t>(n - 1)];
  return {(left ? 1.0 : -1.0) * s.a * std::sin(theta), kCageCentreY - s.b * std::cos(theta),
          RibHead(n) - s.drop * (1.0 - std::cos(theta)) / 2.0};
}

// The inside of the rib cage at height z: an ellipse through the ribs' lateral points, 7 mm in.
// Below the cage, the abdomen inside its wall.
std::pair<double, double> InteriorAxes(double z) {
  std::array<double, 12> mid{};
  for (int n = 1; n <= 12; ++n)
    mid[static_cast<std::size_t>(n - 1)] = RibHead(n) - Ribs()[static_cast<std::size_t>(n - 1)].drop / 2;
  double a = Ribs()[0].a, b = Ribs()[0].b;
  if (z <= mid[11]) {
    const double abdomen_a = kBodyA - kSkin - kFat - kAbdominalMuscle,
                 abdomen_b = kBodyB - kSkin - kFat - kAbdominalMuscle;
    const double w = std::clamp((mid[11] - z) / 0.03, 0.0, 1.0);
    a = (1 - w) * (Ribs()[11].a - 0.007) + w * abdomen_a;
    b = (1 - w) * (Ribs()[11].b - 0.007) + w * abdomen_b;
    return {a, b};
  }
  for (int n = 1; n < 12; ++n)
    if (z <= mid[static_cast<std::size_t>(n - 1)] && z >= mid[static_cast<std::size_t>(n)]) {
      const double w = (mid[static_cast<std::size_t>(n - 1)] - z) /
                       (mid[static_cast<std::size_t>(n - 1)] - mid[static_cast<std::size_t>(n)]);
      a = (1 - w) * Ribs()[static_cast<std::size_t>(n - 1)].a + w * Ribs()[static_cast<std::size_t>(n)].a;
      b = (1 - w) * Ribs()[static_cast<std::size_t>(n - 1)].b + w * Ribs()[static_cast<std::size_t>(n)].b;
    }
  return {a - 0.007, b - 0.007};
}

// The diaphragm's mid-surface z = h(x, y): a higher right dome (over the liver) and a lower left
// one, falling to the costal margin laterally and to the crura on the spine posteriorly.
double DiaphragmHeight(double x, double y) {
  const double domes =
      0.005 + 0.030 * std::exp(-std::pow((x + 0.075) / 0.06, 2)) + 0.018 * std::exp(-std::pow((x - 0.07) / 0.055, 2));
  const double lateral = std::max(0.0, std::abs(x) - 0.06);
  const double posterior = std::min(0.0, y + 0.02);
  // The crura: beside the spine the diaphragm runs down the vertebral bodies to L1-L3.
  const double crura = std::min(0.0, y) * std::exp(-std::pow(x / 0.05, 2));
  return domes - 15.7 * lateral * lateral - 6.5 * (y - 0.03) * (y - 0.03) - 9.6 * posterior * posterior -
         70.0 * crura * crura;
}
// Signed distance (approximately) from the diaphragm's mid-surface, positive above it.
double AboveDiaphragm(double x, double y, double z) {
  const double e = 1e-4;
  const double gx = (DiaphragmHeight(x + e, y) - DiaphragmHeight(x - e, y)) / (2 * e);
  const double gy = (DiaphragmHeight(x, y + e) - DiaphragmHeight(x, y - e)) / (2 * e);
  return (z - DiaphragmHeight(x, y)) / std::sqrt(1.0 + gx * gx + gy * gy);
}
constexpr double kDiaphragmHalfThickness = 0.0025;  // 5 mm sheet (seed 3.2.3: about 3 mm; one voxel more here)

bool InTendon(double x, double y) { return std::pow((x + 0.02) / 0.075, 2) + std::pow((y - 0.045) / 0.03, 2) < 1.0; }

bool InSpine(double x, double y) {
  const bool body = x * x + (y + 0.06) * (y + 0.06) < 0.02 * 0.02;
  const bool canal = x * x + (y + 0.087) * (y + 0.087) < 0.008 * 0.008;
  const bool spinous = std::abs(x) < 0.006 && y > -0.108 && y < -0.08;
  const bool arch = std::abs(x) < 0.035 && y > -0.092 && y < -0.074;
  return (body || spinous || arch) && !canal;
}

bool InLiverShape(double x, double y, double z) {
  const bool ellipsoid =
      std::pow((x + 0.045) / 0.11, 2) + std::pow((y - 0.01) / 0.085, 2) + std::pow((z + 0.03) / 0.09, 2) < 1.0;
  const bool above_inferior_border = z > -0.12 + 0.45 * (x + 0.10);
  return ellipsoid && above_inferior_border && x < 0.10 && AboveDiaphragm(x, y, z) < -kDiaphragmHalfThickness;
}

double DistanceToSegment(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const Eigen::Vector3d ab = b - a;
  const double t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  return (p - (a + t * ab)).norm();
}
// Ascending colon and hepatic flexure into the transverse colon, 5 cm across.
double DistanceToColonAxis(const Eigen::Vector3d& p) {
  const Eigen::Vector3d flexure(-0.11, 0.04, -0.155);
  return std::min(DistanceToSegment(p, flexure, Eigen::Vector3d(0.12, 0.05, -0.145)),
                  DistanceToSegment(p, flexure, Eigen::Vector3d(-0.11, 0.0, -0.26)));
}

std::int16_t Hounsfield(std::uint8_t l) {
  // Unenhanced CT, typical values (docs/biopsy-patient.md).
  switch (l) {
    case label::kAir:
      return -1000;
    case label::kSkin:
      return 30;
    case label::kFat:
      return -100;
    case label::kMuscle:
      return 45;
    case label::kSpine:
      return 400;
    case label::kSternum:
      return 450;
    case label::kLung:
      return -850;
    case label::kCostophrenicRecess:
      return -500;
    case label::kDiaphragmMuscle:
      return 50;
    case label::kDiaphragmTendon:
      return 70;
    case label::kLiver:
      return 60;
    case label::kLiverCapsule:
      return 75;
    case label::kTumour:
      return 30;
    case label::kGallbladder:
      return 10;
    case label::kColon:
      return 40;
    case label::kSoftTissue:
      return 40;
    default:
      break;
  }
  const label::RibOf rib = label::RibOfLabel(l);
  if (rib.number == 0) return 0;
  if (l == label::Rib(rib.left, rib.number)) return 700;
  if (l == label::Cartilage(rib.left, rib.number)) return 120;
  return 40;  // intercostal vein, artery and nerve
}

}  // namespace

PatientVolume GenerateSyntheticPatient(const SyntheticPatientOptions& options) {
  const double h = options.spacing_m;
  if (!(h >= 0.001 && h <= 0.004)) throw std::invalid_argument("synthetic patient: spacing_m must be 1-4 mm");
  PatientVolume out;
  physics::LabelVolume& v = out.labels;
  v.dims = {static_cast<int>(std::lround(2 * kHalfX / h)), static_cast<int>(std::lround(2 * kHalfY / h)),
            static_cast<int>(std::lround(2 * kHalfZ / h))};
  v.spacing_m = Eigen::Vector3d::Constant(h);
  v.direction = Eigen::Vector3d(-1.0, 1.0, 1.0).asDiagonal();  // i runs to the patient's right
  v.origin_m = Eigen::Vector3d(kHalfX - h / 2, -kHalfY + h / 2, -kHalfZ + h / 2);
  v.labels.assign(static_cast<std::size_t>(v.dims[0]) * v.dims[1] * v.dims[2], label::kAir);
  out.hu.assign(v.labels.size(), 0);

  const SyntheticTumour tumour;
  const Eigen::Vector3d tumour_centre(tumour.x_m, tumour.y_m, tumour.z_m);
  const Eigen::Vector3d heart_centre(0.025, 0.035, DiaphragmHeight(0.02, 0.03) + 0.06);
  for (int k = 0; k < v.dims[2]; ++k) {
    const double z = v.Position(0, 0, k).z();
    const auto [ia, ib] = InteriorAxes(z);
    for (int j = 0; j < v.dims[1]; ++j)
      for (int i = 0; i < v.dims[0]; ++i) {
        const Eigen::Vector3d p = v.Position(i, j, k);
        const double x = p.x(), y = p.y();
        const double r = std::hypot(x / kBodyA, y / kBodyB);
        if (r >= 1.0) continue;  // air
        const double depth = (1.0 - r) * (r > 1e-9 ? std::hypot(x, y) / r : kBodyB);
        std::uint8_t l = label::kSoftTissue;
        const double interior = std::hypot(x / ia, (y - kCageCentreY) / ib);
        const double above = AboveDiaphragm(x, y, z);
        if (depth < kSkin) {
          l = label::kSkin;
        } else if (depth < kSkin + kFat) {
          l = label::kFat;
        } else if (interior >= 1.0) {
          l = label::kMuscle;
        } else if (std::abs(above) <= kDiaphragmHalfThickness) {
          l = InTendon(x, y) ? label::kDiaphragmTendon : label::kDiaphragmMuscle;
        } else if (above > 0.0) {  // thorax
          const bool mediastinum = std::abs(x - 0.005) < 0.035 || std::pow((x - heart_centre.x()) / 0.065, 2) +
                                                                          std::pow((y - heart_centre.y()) / 0.05, 2) +
                                                                          std::pow((z - heart_centre.z()) / 0.06, 2) <
                                                                      1.0;
          if (!mediastinum) {
            const bool recess = above < kDiaphragmHalfThickness + 0.015 && interior > 1.0 - 0.02 / std::min(ia, ib);
            l = recess ? label::kCostophrenicRecess : label::kLung;
          }
        } else {  // abdomen
          if (std::pow((x + 0.035) / 0.018, 2) + std::pow((y - 0.05) / 0.04, 2) + std::pow((z + 0.095) / 0.016, 2) <
              1.0)
            l = label::kGallbladder;
          else if (InLiverShape(x, y, z))
            l = (p - tumour_centre).norm() < tumour.radius_m ? label::kTumour : label::kLiver;
          else if (DistanceToColonAxis(p) < 0.025)
            l = label::kColon;
        }
        if (InSpine(x, y) && depth >= kSkin + kFat) l = label::kSpine;
        if (std::abs(x) < 0.018 && std::abs(y - 0.095) < 0.006 && z > -0.045 && z < 0.158) l = label::kSternum;
        v.labels[v.Index(i, j, k)] = l;
      }
  }

  // Ribs, their cartilage and the neurovascular bundle in each costal groove, drawn along their
  // centre lines: 12 mm tall, 7 mm thick (cartilage 10 x 6 mm), bundle 4 mm across, 8.5 mm below.
  const Eigen::Matrix3d to_index = (v.direction * v.spacing_m.asDiagonal()).inverse();
  const auto stamp = [&](const Eigen::Vector3d& c, double half_height, double half_radial, auto&& write) {
    const double reach = std::max(half_height, half_radial);
    const Eigen::Vector3d lo = to_index * (c - Eigen::Vector3d::Constant(reach) - v.origin_m);
    const Eigen::Vector3d hi = to_index * (c + Eigen::Vector3d::Constant(reach) - v.origin_m);
    for (int k = std::max(0, static_cast<int>(std::floor(std::min(lo.z(), hi.z()))));
         k <= std::min(v.dims[2] - 1, static_cast<int>(std::ceil(std::max(lo.z(), hi.z())))); ++k)
      for (int j = std::max(0, static_cast<int>(std::floor(std::min(lo.y(), hi.y()))));
           j <= std::min(v.dims[1] - 1, static_cast<int>(std::ceil(std::max(lo.y(), hi.y())))); ++j)
        for (int i = std::max(0, static_cast<int>(std::floor(std::min(lo.x(), hi.x()))));
             i <= std::min(v.dims[0] - 1, static_cast<int>(std::ceil(std::max(lo.x(), hi.x())))); ++i) {
          const Eigen::Vector3d d = v.Position(i, j, k) - c;
          if (std::pow(d.z() / half_height, 2) + (d.x() * d.x() + d.y() * d.y()) / (half_radial * half_radial) <= 1.0)
            write(v.labels[v.Index(i, j, k)]);
        }
  };
  for (int side = 0; side < 2; ++side)
    for (int n = 1; n <= 12; ++n) {
      const bool left = side == 1;
      const RibShape& s = Ribs()[static_cast<std::size_t>(n - 1)];
      const double theta0 = std::asin(0.03 / s.a);
      const int samples = static_cast<int>(std::ceil((s.theta_end - theta0) * s.a / 0.0005));
      for (int q = 0; q <= samples; ++q) {
        const double theta = theta0 + (s.theta_end - theta0) * q / samples;
        const Eigen::Vector3d c = RibPoint(n, left, theta);
        const bool bone = theta <= s.theta_bone;
        stamp(c, bone ? 0.006 : 0.005, bone ? 0.0035 : 0.003, [&](std::uint8_t& l) {
          if (l != label::kSpine && l != label::kSternum) l = bone ? label::Rib(left, n) : label::Cartilage(left, n);
        });
        if (!bone) continue;
        const Eigen::Vector3d inward = -Eigen::Vector3d(c.x(), c.y() - kCageCentreY, 0.0).normalized();
        stamp(c + Eigen::Vector3d(0, 0, -0.0085) + 0.001 * inward, 0.002, 0.002, [&](std::uint8_t& l) {
          if (label::RibOfLabel(l).number == 0 && l != label::kSpine && l != label::kSternum)
            l = label::Bundle(left, n);
        });
      }
    }

  // No slivers: an opening (erode, dilate by one voxel) of the liver drops parts under two voxels
  // thick (where its shape meets the crura), which a mesh could not follow.
  {
    const auto liver_at = [&](const std::vector<std::uint8_t>& mask, int i, int j, int k) {
      return i >= 0 && j >= 0 && k >= 0 && i < v.dims[0] && j < v.dims[1] && k < v.dims[2] && mask[v.Index(i, j, k)];
    };
    std::vector<std::uint8_t> liver(v.labels.size()), eroded(v.labels.size(), 0);
    for (std::size_t q = 0; q < liver.size(); ++q) liver[q] = label::IsLiver(v.labels[q]);
    const int step[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    for (int k = 0; k < v.dims[2]; ++k)
      for (int j = 0; j < v.dims[1]; ++j)
        for (int i = 0; i < v.dims[0]; ++i) {
          if (!liver[v.Index(i, j, k)]) continue;
          bool all = true;
          for (const auto& s : step) all = all && liver_at(liver, i + s[0], j + s[1], k + s[2]);
          eroded[v.Index(i, j, k)] = all;
        }
    for (int k = 0; k < v.dims[2]; ++k)
      for (int j = 0; j < v.dims[1]; ++j)
        for (int i = 0; i < v.dims[0]; ++i) {
          const std::size_t q = v.Index(i, j, k);
          if (!liver[q] || eroded[q]) continue;
          bool kept = false;
          for (const auto& s : step) kept = kept || liver_at(eroded, i + s[0], j + s[1], k + s[2]);
          if (!kept) v.labels[q] = label::kSoftTissue;
        }
  }

  // The capsule: the liver's outer voxel layer; and a check that the tumour lies inside the liver.
  std::vector<std::uint8_t> capsule(v.labels.size(), 0);
  for (int k = 1; k + 1 < v.dims[2]; ++k)
    for (int j = 1; j + 1 < v.dims[1]; ++j)
      for (int i = 1; i + 1 < v.dims[0]; ++i) {
        if (v.At(i, j, k) != label::kLiver) continue;
        const std::uint8_t around[] = {v.At(i - 1, j, k), v.At(i + 1, j, k), v.At(i, j - 1, k),
                                       v.At(i, j + 1, k), v.At(i, j, k - 1), v.At(i, j, k + 1)};
        for (std::uint8_t a : around)
          if (!label::IsLiver(a)) capsule[v.Index(i, j, k)] = 1;
      }
  for (std::size_t q = 0; q < capsule.size(); ++q)
    if (capsule[q]) v.labels[q] = label::kLiverCapsule;
  for (int k = 0; k < v.dims[2]; ++k)
    for (int j = 0; j < v.dims[1]; ++j)
      for (int i = 0; i < v.dims[0]; ++i)
        if ((v.Position(i, j, k) - tumour_centre).norm() < tumour.radius_m + 0.003 && !label::IsLiver(v.At(i, j, k)))
          throw std::logic_error("synthetic patient: the tumour is not inside the liver");

  // Hounsfield units, with the colon's gas and the intervertebral discs.
  for (int k = 0; k < v.dims[2]; ++k)
    for (int j = 0; j < v.dims[1]; ++j)
      for (int i = 0; i < v.dims[0]; ++i) {
        const std::size_t q = v.Index(i, j, k);
        const Eigen::Vector3d p = v.Position(i, j, k);
        std::int16_t hu = Hounsfield(v.labels[q]);
        if (v.labels[q] == label::kColon && DistanceToColonAxis(p) < 0.017) hu = -900;
        if (v.labels[q] == label::kSpine && std::fmod(RibHead(1) + 0.0115 - p.z() + 1.0, 0.023) < 0.004) hu = 90;
        out.hu[q] = hu;
      }
  return out;
}

}  // namespace vesica::app::patient
