#include "app/anatomy/surgeon_view_layout.h"

#include <algorithm>

namespace vesica::app::anatomy {

RetractedLiverShape SurgeonViewLiver() { return RetractedLiverShape{}; }

GallbladderCentreline SurgeonViewGallbladder(const LiverSurfaceFrame& f) {
  GallbladderCentreline c;
  // (s along the edge toward the left lobe, u from the edge toward the hilum, q out of the
  // visceral surface), metres. The fundus lies past the edge (u < 0), pushed over it; near the
  // edge, where the liver is thin, the gallbladder rides above the visceral surface (the edge
  // stays whole under it), and it sinks into its shallow fossa toward the infundibulum, where the
  // liver is thick. Hartmann's pouch and the duct stub lie toward the hilum.
  c.points_m = {f.At(-0.018, -0.004, 0.008),  // fundus, over the edge
                f.At(0.000, 0.020, -0.002),   // body
                f.At(0.006, 0.044, -0.003),   // infundibulum
                f.At(0.012, 0.064, -0.002),   // Hartmann's pouch
                f.At(0.020, 0.074, -0.001),   // neck
                f.At(0.028, 0.078, 0.001)};   // cut end of the cystic-duct stub
  c.radii_m = {0.011, 0.0135, 0.0125, 0.009, 0.005, 0.003};
  c.blend_m = 0.004;
  return c;
}

AnatomyOptions SurgeonViewAnatomyOptions() {
  AnatomyOptions o;
  const RetractedLiverShape liver = SurgeonViewLiver();
  o.gallbladder = SurgeonViewGallbladder(liver.frame);
  o.liver_field = [liver, gallbladder = o.gallbladder](const Eigen::Vector3d& p) {
    return RetractedLiverField(liver, gallbladder, p);
  };
  o.liver_field_bounds = RetractedLiverBounds(liver);
  // Graded: 2.5 mm edges along the border's thin crest and 5 mm in the fossa (where the
  // connective tissue attaches), 14 mm far from both, so that the crest is drawn smooth rather
  // than as a saw with the BEM's thousand vertices.
  o.liver_relaxation_iterations = 30;
  o.liver_edge_length_m = [liver, gallbladder = o.gallbladder](const Eigen::Vector3d& p) {
    const double crest = 0.0025 + 0.0115 * std::min(1.0, RetractedLiverCrestDistance(liver, p) / 0.04);
    const double fossa = 0.005 + 0.009 * std::clamp(GallbladderDistance(gallbladder, p) / 0.03, 0.0, 1.0);
    return std::min(crest, fossa);
  };
  // The bed is the fossa's medial rim (toward the left lobe, at or above the gallbladder's axis):
  // the springs grow toward it, so the connective tissue lies in the slot the camera looks into.
  o.liver_labels.bed_side_direction = liver.frame.Along();
  o.liver_labels.bed_side_min_m = 0.0;
  o.liver_labels.bed_distance_m = 0.012;
  o.liver_labels.bed_height_direction = liver.frame.Out();
  o.liver_labels.bed_height_min_m = -0.002;
  // The bare area and the vena cava groove: the back of the wedge, deep to the hilum.
  o.liver_labels.fixed_centre_m = liver.frame.At(-0.02, 0.085, -0.045);
  o.liver_labels.fixed_semi_axes_m = {0.07, 0.04, 0.04};
  o.gallbladder_resolutions = {{1000, 550}};
  // American four-port technique, the surgeon on the patient's left: the left hand's grasper at
  // the right midclavicular line under the costal margin, the right hand's hook epigastric just
  // left of the midline, the laparoscope at the umbilicus (the assistant's anterior-axillary
  // port holds the fundus; it carries no simulated instrument).
  o.ports.grasper_xz_m = {-0.08, 0.03};
  o.ports.cautery_xz_m = {0.01, 0.037};
  o.ports.laparoscope_xz_m = {0.0, -0.10};
  return o;
}

}  // namespace vesica::app::anatomy
