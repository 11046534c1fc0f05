// Binding points of the multi-view shadow-map techniques (src/techniques/shadow_map/maps.h: mvr,
// vwss, reproject), valid in C++ and GLSL. Shared ones are in shared/shared.h (see dcs_bindings.h).
#ifndef PENUMBRA_SHADOW_MAP_BINDINGS_H
#define PENUMBRA_SHADOW_MAP_BINDINGS_H

#define PENUMBRA_UNIT_SHADOW_MAPS 12    // multi-view depth maps (techniques/shadow_map): a layer a sample
#define PENUMBRA_UNIT_CENTRAL_DEPTH 13  // reproject: the z-buffered central depth map
#define PENUMBRA_UNIT_SEMI_COUNT 14     // R32UI 2D array: semi-opaque surfaces on each map texel
#define PENUMBRA_UNIT_SEMI_LAYERS 15    // R32UI 2D array: K entries a map (shadow_map/maps.h)
#define PENUMBRA_IMAGE_SHADOW_MAPS 1    // R32UI 2D array: point-rendered depth maps (atomicMax)
#define PENUMBRA_IMAGE_SEMI_COUNT 2     // R32UI 2D array: semi-opaque surfaces a texel (atomicAdd)
#define PENUMBRA_IMAGE_SEMI_LAYERS 3    // R32UI 2D array: their entries (depth and opacity)
#define PENUMBRA_IMAGE_SEMI_STATUS 4    // R32UI 1 x 1: most semi-opaque surfaces on one map texel
#define PENUMBRA_SSBO_POINTS 7          // vwss: point count, then xyz world positions (3 floats each)
// The frustum fit of every shadow-map technique, single-view too (src/techniques/common/shadow_map/shaders/shadow_map_fit.comp).
#define PENUMBRA_IMAGE_MAP_OUTSIDE 6    // R32UI G-buffer size: receivers outside the shadow maps
#define PENUMBRA_SSBO_MAP_FIT 13        // the fit's results, then a sum a G-buffer row
#define PENUMBRA_MAP_LOCAL_SIZE 64      // threads per work group of the point reprojection

#endif
