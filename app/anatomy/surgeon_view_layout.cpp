#include "app/anatomy/surgeon_view_layout.h"

namespace vesica::app::anatomy {

RetractedLiverShape SurgeonViewLiver() { return RetractedLiverShape{}; }

GallbladderCentreline SurgeonViewGallbladder(const LiverSurfaceFrame& f) {
  GallbladderCentreline c;
  // (s along the edge toward the left lobe, u from the edge toward the hilum, q out of the
  // visceral surface), metres. The fundus lies past the edge (u < 0) and behind the surface's
  // plane (q < 0): pushed over the edge. The body's axis sits 2 mm inside that plane.
  c.points_m = {f.At(-0.018, -0.016, -0.009),  // fundus, over the edge
                f.At(0.000, 0.008, -0.002),    // body
                f.At(0.006, 0.034, -0.004),    // infundibulum
                f.At(0.012, 0.054, -0.002),    // Hartmann's pouch
                f.At(0.020, 0.064, -0.001),    // neck
                f.At(0.028, 0.068, 0.001)};    // cut end of the cystic-duct stub
  c.radii_m = {0.012, 0.0135, 0.0125, 0.009, 0.005, 0.003};
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
  o.liver_relaxation_iterations = 4;
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
  o.ports.cautery_xz_m = {0.01, 0.045};
  o.ports.laparoscope_xz_m = {0.0, -0.10};
  return o;
}

}  // namespace vesica::app::anatomy
