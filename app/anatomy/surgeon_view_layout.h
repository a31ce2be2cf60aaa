#pragma once
// The anatomy of the surgeon's view (data/anatomy/surgeon-view/): the liver retracted so that
// its visceral surface faces the umbilical laparoscope, the gallbladder in its fossa with the
// fundus pushed over the inferior edge by the assistant, Hartmann's pouch and the cystic duct
// toward the hilum, ports of the American four-port technique. See docs/anatomy.md.

#include "app/anatomy/anatomy_generator.h"
#include "app/anatomy/retracted_liver_shape.h"

namespace vesica::app::anatomy {

/// The retracted liver of the surgeon's view.
RetractedLiverShape SurgeonViewLiver();

/// Its gallbladder, placed in the liver's surface frame: fundus over the edge, body in the fossa
/// (sunk a few millimetres, so that the fossa's medial rim stands beside it), Hartmann's pouch
/// and the duct stub toward the hilum.
GallbladderCentreline SurgeonViewGallbladder(const LiverSurfaceFrame& frame);

/// Generator options for the surgeon's view: that liver and gallbladder, the medial rim of the
/// fossa as the bed, the bare area fixed, one gallbladder resolution (1000 nodes), the ports.
AnatomyOptions SurgeonViewAnatomyOptions();

}  // namespace vesica::app::anatomy
