// Scenes made in memory from another, for studies (study/study_file.h SceneEntry, light-scales)
// and benchmarks: a scene's lights scaled, its materials made opaque, its occluders instanced.
// A variant is written as "key=value" strings; checkSceneVariant refuses what applySceneVariant
// could not apply, with the place it was written.
#pragma once

#include <string>
#include <vector>

#include "core/key_values.h"
#include "scene/scene.h"

namespace penumbra {

// Every light's extent (a rect's sides, a disk's or a sphere's radius) times `scale`.
Scene withLightsScaled(Scene scene, double scale);

// Every mesh but the first (the floor) repeated `copies` times (1-9) on a 3 x 3 grid of cells
// `spacing` apart in x and z: the VWSS paper's scenes of growing triangle counts.
Scene withOccludersInstanced(const Scene& base, int copies, float spacing);

// The keys of a variant: "opacity" (every material's opacity, [0, 1]: 1 makes the opaque twin of
// a semi-opaque scene), "copies" (1-9) and "spacing" (> 0, default 1) of
// withOccludersInstanced.
const std::vector<std::string>& sceneVariantKeys();
void checkSceneVariant(const std::vector<std::string>& variant, const KeyPlace& place);
Scene applySceneVariant(Scene scene, const std::vector<std::string>& variant);

}  // namespace penumbra
