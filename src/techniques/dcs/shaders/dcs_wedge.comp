// The compute path of the counter pass (dcs `path=compute`): the wedges binned into screen tiles
// and evaluated per pixel there, in place of rasterising their front faces (dcs_wedge.geom).
// The raster path's fill is the surfaces behind each front face, most of which lie
// outside the solid; here a tile keeps the edges whose solid meets the bounding box of its
// visible points (tiled light culling, with the wedge solids as the lights) and a pixel runs the
// update (common_dcs_update.glsl, the raster path's function) only where its point is inside the
// solid. Every (pixel, edge) pair is seen at most once by construction, with no depth test.
//
// The counts are integers per sample in the invocation, added to the initialised counters
// (dcs_init.frag) once at the end: nothing is blended, so the packing only has to hold the
// final counts, not a bound on the partial sums (dcs_wedge.frag). Each final count is checked
// here: one past its digit is clamped and reported through the checksum's bound (the largest
// count of the pixel, dcs.cpp renders again with the base it needs), one below zero is stored as
// 0, which the resolve reports as a negative count.
#include "shared/numerics.h"
#include "common_light.glsl"
#include "common_dcs.glsl"
#include "common_dcs_pass.glsl"
#include "common_dcs_lut.glsl"
const int PASS_SAMPLES = DCS_TARGETS * 4 * DIGITS;
const int MASK_WORDS = (PASS_SAMPLES + 31) / 32;
#include "common_dcs_update.glsl"
#include "dcs_solid.glsl"

#define TILE PENUMBRA_DCS_TILE
layout(local_size_x = TILE, local_size_y = TILE) in;

layout(binding = PENUMBRA_UNIT_GBUF_POSITION) uniform sampler2D gPosition;
layout(binding = PENUMBRA_UNIT_GBUF_NORMAL) uniform sampler2D gNormal;
layout(binding = PENUMBRA_IMAGE_DCS_COUNTERS, rgba32f) uniform image2DArray counterImage;
layout(binding = PENUMBRA_IMAGE_DCS_CHECKSUM, rgba32f) uniform image2D checksumImage;
layout(std430, binding = PENUMBRA_SSBO_DCS_SOLIDS) readonly buffer DcsSolids { DcsSolidPlanes dcsSolids[]; };
uniform vec3 eyePosition;
// The running counts of the pass between dispatches, PASS_SAMPLES a pixel, and the chunks the
// tiles completed (dcs.cpp checks them: llvmpipe cuts long loops short, see below).
layout(std430, binding = PENUMBRA_SSBO_DCS_COUNTS) buffer DcsCounts {
  uint chunksDone;
  int dcsCounts[];
};

// Floats as unsigned integers in the same order (for the shared atomics of the box).
uint orderedBits(float f) {
  uint u = floatBitsToUint(f);
  return (u & 0x80000000u) != 0u ? ~u : u | 0x80000000u;
}
float fromOrdered(uint u) { return uintBitsToFloat((u & 0x80000000u) != 0u ? u & 0x7fffffffu : ~u); }

shared uint boxLo[3], boxHi[3];
shared uint listCount;
shared uint list[TILE * TILE];

// The solids are read a plane at a time, the end planes only once the five have passed: a copy
// of the whole 224-byte solid per test made the loop slower than the planes it saved.
// Does solid i meet the box (centre, extent) of the tile's points, or (a rectangle) the tile's
// NDC rectangle?
bool meetsTile(uint i, vec3 centre, vec3 extent, vec4 tileNdc) {
  if (dcsSolids[i].meta.x == DCS_SOLID_RECT) {
    vec4 r = dcsSolids[i].plane[0];
    return r.x <= tileNdc.z && tileNdc.x <= r.z && r.y <= tileNdc.w && tileNdc.y <= r.w;
  }
  for (int k = 0; k < 5; ++k) {
    vec4 q = dcsSolids[i].plane[k];
    if (dot(q.xyz, centre) + dot(abs(q.xyz), extent) < q.w) return false;
  }
  int sides = dcsSolids[i].meta.z;
  for (int k = 0; k < sides; ++k) {
    vec4 q = dcsSolids[i].side[k];
    if (dot(q.xyz, centre) + dot(abs(q.xyz), extent) < q.w) return false;
  }
  return true;
}

// Is p inside solid i?
bool inside(uint i, vec3 p) {
  if (dcsSolids[i].meta.x == DCS_SOLID_RECT) return true;
  for (int k = 0; k < 5; ++k) {
    vec4 q = dcsSolids[i].plane[k];
    if (dot(q.xyz, p) < q.w) return false;
  }
  int sides = dcsSolids[i].meta.z;
  for (int k = 0; k < sides; ++k) {
    vec4 q = dcsSolids[i].side[k];
    if (dot(q.xyz, p) < q.w) return false;
  }
  return true;
}

void main() {
  ivec2 size = textureSize(gPosition, 0);
  ivec2 px = ivec2(gl_GlobalInvocationID.xy);
  uint lid = gl_LocalInvocationIndex;
  bool valid = px.x < size.x && px.y < size.y;
  vec3 p = vec3(0.0);
  if (valid) {
    vec4 gp = texelFetch(gPosition, px, 0);
    valid = gp.w != 0.0;
    // The raster path's evaluation point (dcs_wedge.frag).
    if (valid) p = penumbraShadowOrigin(gp.xyz, texelFetch(gNormal, px, 0).xyz, eyePosition);
  }
  if (lid < 3u) {
    boxLo[lid] = 0xffffffffu;
    boxHi[lid] = 0u;
  }
  barrier();
  if (valid)
    for (int k = 0; k < 3; ++k) {
      atomicMin(boxLo[k], orderedBits(p[k]));
      atomicMax(boxHi[k], orderedBits(p[k]));
    }
  barrier();
  if (boxLo[0] > boxHi[0]) {  // no visible point in the tile (the whole group returns)
    if (lid == 0u) atomicAdd(chunksDone, (solidEnd - solidFirst + uint(TILE * TILE) - 1u) / uint(TILE * TILE));
    return;
  }
  vec3 lo = vec3(fromOrdered(boxLo[0]), fromOrdered(boxLo[1]), fromOrdered(boxLo[2]));
  vec3 hi = vec3(fromOrdered(boxHi[0]), fromOrdered(boxHi[1]), fromOrdered(boxHi[2]));
  vec3 centre = 0.5 * (lo + hi), extent = 0.5 * (hi - lo);
  vec2 t0 = vec2(gl_WorkGroupID.xy * uint(TILE)), t1 = t0 + vec2(TILE);
  vec4 tileNdc = vec4(2.0 * t0 / vec2(size) - 1.0, 2.0 * t1 / vec2(size) - 1.0);

  // The solids come in several dispatches of a few chunks each: in one long loop over all of
  // them llvmpipe (Mesa 22.3) stopped a tile after about 40 chunks on the engine (its loop
  // limiter), silently. The chunks each tile completes are counted and checked.
  int count[PASS_SAMPLES];
  uint slot = (uint(px.y) * uint(size.x) + uint(px.x)) * uint(PASS_SAMPLES);
  for (int j = 0; j < PASS_SAMPLES; ++j) count[j] = valid ? dcsCounts[slot + uint(j)] : 0;
  uint chunks = 0u;
  for (uint first = solidFirst; first < solidEnd; first += uint(TILE * TILE)) {
    if (lid == 0u) listCount = 0u;
    barrier();
    uint i = first + lid;
    if (i < solidEnd && meetsTile(i, centre, extent, tileNdc) &&
        !dcsEdgeWeighsNothingInBox(dcsEdges[dcsSolids[i].meta.y], centre, extent))
      list[atomicAdd(listCount, 1u)] = i;
    barrier();
    uint n = listCount;
    if (valid) {
      PROFILE_ADD(profCandidates, n);
      for (uint k = 0u; k < n; ++k) {
        uint i = list[k];
        if (!inside(i, p)) continue;
        PROFILE_COUNT(profFragments);
        uint mask[MASK_WORDS];
        int delta = dcsEdgeUpdate(px, p, dcsSolids[i].meta.y, passFirst, passCount, mask);
        if (delta == 0) continue;
        bool updating = false;
        for (int w = 0; w < MASK_WORDS; ++w) {
          uint bits = mask[w];
          updating = updating || bits != 0u;
          while (bits != 0u) {
            int b = findLSB(bits);
            count[w * 32 + b] += delta;
            bits &= bits - 1u;
          }
        }
        if (updating) PROFILE_COUNT(profUpdating);
      }
    }
    barrier();
    ++chunks;
  }
  if (lid == 0u) atomicAdd(chunksDone, chunks);
  if (!valid) return;
  if (finalDispatch == 0) {
    for (int j = 0; j < PASS_SAMPLES; ++j) dcsCounts[slot + uint(j)] = count[j];
    return;
  }

  // The final counts: the initialised digits (D(c) + bias + path crossings) plus the updates.
  float total = 0.0, weighted = 0.0, largest = 0.0;
  for (int t = 0; t < DCS_TARGETS; ++t) {
    vec4 v = imageLoad(counterImage, ivec3(px, t));
    for (int ch = 0; ch < 4; ++ch) {
      float value = v[ch], repacked = 0.0, weight = 1.0;
      for (int d = 0; d < DIGITS; ++d, weight *= float(DCS_BASE)) {
        float q = floor(value / float(DCS_BASE));
        float digit = value - q * float(DCS_BASE);
        value = q;
        int j = (t * 4 + ch) * DIGITS + d;
        if (uint(j) < passCount) {
          float c = digit + float(count[j]);
          total += float(count[j]);
          weighted += float((j + 1) * count[j]);
          largest = max(largest, c);
          digit = clamp(c, 0.0, float(DCS_BASE - 1));
        }
        repacked += digit * weight;
      }
      v[ch] = repacked;
    }
    imageStore(counterImage, ivec3(px, t), v);
  }
  vec4 sums = imageLoad(checksumImage, px);
  imageStore(checksumImage, px, vec4(sums.r + total, max(sums.g, largest), sums.b + weighted, 0.0));
}
