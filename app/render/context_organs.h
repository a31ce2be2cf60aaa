#pragma once
// The static context of the operating field (internal to app/render): the scenario's
// [[context_organs]] drawn as smooth tubes (duodenum, colon, bile ducts, cystic artery) and
// ellipsoids (omentum, fat), wet and lit like the organs, never simulated. They make the field
// recognisable: what lies around the gallbladder is what a surgeon orients by.

#include <vtkSmartPointer.h>

#include <vector>

#include "app/scenario/scenario.h"

class vtkActor;

namespace vesica::app {

/// One actor per organ, in the display frame (display_frame.h); `pbr`: physically based
/// (colour taken as sRGB, roughness kContextRoughness) instead of Phong.
std::vector<vtkSmartPointer<vtkActor>> MakeContextOrganActors(const std::vector<ContextOrgan>& organs,
                                                              bool pbr = false);

}  // namespace vesica::app
