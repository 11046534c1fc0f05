// Binding points of dcs (src/techniques/dcs), valid in C++ and GLSL: texture and image units and
// shader-storage bindings of its passes. Shared ones (G-buffer, light samples, counter) are in
// shared/shared.h; a technique's own may reuse another technique's numbers (one technique draws at a
// time), never the shared ones.
#ifndef PENUMBRA_DCS_BINDINGS_H
#define PENUMBRA_DCS_BINDINGS_H

#define PENUMBRA_UNIT_DCS_COUNTERS 7    // RGBA32F 2D array: dcs packed counters, a layer a target
#define PENUMBRA_UNIT_DCS_CHECKSUM 8    // R32F: dcs sum of the counters of a pass
#define PENUMBRA_UNIT_DCS_SECTOR_LUT 9  // RGBA32UI cube-map array: dcs edge LUT, sectors (a cube a set)
#define PENUMBRA_UNIT_DCS_LINE_LUT 10   // RGBA32UI 2D array: dcs edge LUT, lines (a layer a set)
#define PENUMBRA_IMAGE_DCS_PROFILE 5    // R32UI 7 x 1: dcs wedge counters (PENUMBRA_DCS_PROFILE=1)
#define PENUMBRA_IMAGE_DCS_COUNTERS 6   // RGBA32F 2D array: the packed counters, compute path (read-write)
#define PENUMBRA_IMAGE_DCS_CHECKSUM 7   // RG32F: the checksum target, compute path (read-write)
#define PENUMBRA_DCS_TILE 8            // dcs compute path: a work group's tile is TILE x TILE pixels
#define PENUMBRA_SSBO_DCS_EDGES 2       // dcs: edges (endpoints, incidence range, rule)
#define PENUMBRA_SSBO_DCS_INCIDENCES 3  // dcs: incident triangles (third vertex, plane normal)
#define PENUMBRA_SSBO_DCS_STATUS 4      // dcs: resolve status (overflowing pixels)
#define PENUMBRA_SSBO_DCS_PASS 5        // dcs: the pass's sample range (common_dcs_pass.glsl)
#define PENUMBRA_SSBO_DCS_PACKED 6      // dcs: packed sample positions (edge_lut.h), naive mode
#define PENUMBRA_SSBO_DCS_PATH_FIRST 11  // dcs: per light sample, the first of its path crossings (then the end)
#define PENUMBRA_SSBO_DCS_PATH 12        // dcs: path crossings (triangle plane, sides, rule, units)
#define PENUMBRA_SSBO_DCS_SOLIDS 13      // dcs compute path: the selected edges' wedge solids (dcs_solids.comp)
#define PENUMBRA_SSBO_DCS_EDGE_IDS 14    // dcs compute path: the selected edges' ids
#define PENUMBRA_SSBO_DCS_COUNTS 15      // dcs compute path: the pass's running counts and completed chunks

#endif
