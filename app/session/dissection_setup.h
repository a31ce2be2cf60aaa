#pragma once
// From a scenario and its meshes to the physics scene's inputs: materials, solver, springs and
// the instrument mounts (each instrument pivots about its trocar; yaw = pitch = 0 points the
// shaft at the laparoscope's target, as LaparoscopeView draws it).

#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include "app/render/scene_meshes.h"
#include "app/scenario/scenario.h"
#include "app/session/calot_triangle_step.h"
#include "fx/cautery_effects.h"
#include "physics/scene/dissection_model.h"

namespace vesica::app {

/// Throws std::invalid_argument naming the scenario file when it has no grasper + hook pair.
physics::DissectionModelInputs MakeDissectionInputs(const Scenario& scenario, const SceneMeshes& meshes);

/// The liver's Green's functions take seconds to compute: they are cached per user
/// ($XDG_CACHE_HOME/vesica, else ~/.cache/vesica; $VESICA_CACHE_DIR overrides) under a name
/// derived from the scenario file; the cache checks its own key, so a stale file is rebuilt.
std::filesystem::path BemCachePath(const Scenario& scenario);

/// MakeDissectionInputs + BuildDissectionModel with the BEM cache. A cache that cannot be used
/// (folder not creatable, read-only or full disk, a directory in the way) is logged once as a
/// warning and the model is computed uncached; the precompute's progress is logged.
std::shared_ptr<const physics::DissectionModel> BuildDissectionModelFor(const Scenario& scenario,
                                                                        const SceneMeshes& meshes);

/// Logs `message` as a warning unless this process already logged the same text.
void WarnOncePerProcess(const std::string& message);

/// The scenario's Calot's triangle with the laparoscope's camera (ScopePoseOf, its view angle and
/// `aspect`, the image's width over height); none when the scenario has no [calot_triangle].
std::optional<CalotSessionSetup> CalotSessionSetupFor(const Scenario& scenario, double aspect = 16.0 / 9.0);

/// Cautery settings of a session (fx defaults; the membrane fades in 0.25 s of active contact).
fx::CauteryParams DefaultCauteryParams();

}  // namespace vesica::app
