#pragma once
// Trocar and laparoscope ports of the standard four-port laparoscopic cholecystectomy, placed on
// the abdominal-wall surface, and their ports.toml file.

#include <Eigen/Core>
#include <filesystem>

#include "physics/mesh/triangle_mesh.h"

namespace vesica::app::anatomy {

/// Where the ports go, as (x, z) skin positions in the patient frame (metres); each is dropped
/// onto the wall along -y (from anterior). The surgeon stands on the patient's left: the left
/// hand's grasper enters at the right midclavicular line below the costal margin, the right
/// hand's cautery hook just left of the midline 10 cm above the umbilicus, the laparoscope at
/// the umbilicus. (The fourth, anterior-axillary port is the assistant's and carries no
/// instrument.) The hook's port sits below the liver's inferior edge rather than high in the
/// epigastrium: the gallbladder lies on the liver's visceral surface and our liver is not
/// retracted, so from a high port every straight path to the liver bed would cross the liver.
struct PortSkinPositions {
  Eigen::Vector2d grasper_xz_m{-0.085, 0.05};
  Eigen::Vector2d cautery_xz_m{0.01, 0.0};
  Eigen::Vector2d laparoscope_xz_m{0.0, -0.10};
};

struct PortLayout {
  Eigen::Vector3d grasper_m;      ///< left-hand grasper trocar (remote centre), on the wall
  Eigen::Vector3d cautery_m;      ///< right-hand cautery hook trocar, on the wall
  Eigen::Vector3d laparoscope_m;  ///< umbilical laparoscope port, on the wall
  Eigen::Vector3d look_at_m;      ///< where the laparoscope points: the gallbladder
};

/// Drops each skin position onto `wall`; throws std::runtime_error if one misses the wall.
PortLayout PlacePorts(const physics::TriangleMesh& wall, const PortSkinPositions& skin,
                      const Eigen::Vector3d& look_at_m);

/// Writes [ports.grasper], [ports.cautery] (position_m) and [ports.laparoscope] (position_m,
/// look_at_m) as TOML.
void WritePortsToml(const PortLayout& ports, const std::filesystem::path& path);

}  // namespace vesica::app::anatomy
