// The edge lookup tables of the DCS paper (section 7.3, Fig. 8) and its packed sample positions
// (section 7.1), for the `lut` and `naive` covered-sample modes of dcs. No GL here.
//
// Seen from a point p, an edge projects onto the light's plane as a segment (v0, v1) (clipped to
// the slab between p and the light, src/techniques/dcs/shaders/dcs_wedge.frag). The samples whose path from the
// light centre c crosses it are those in the sector from c between the directions to v0 and v1
// and beyond the segment's line. Two tables give them as bit fields (bit k: sample k of a set):
//  * the sector table, a cube map (default 64x64x6) looked up with the direction (x, y, 0):
//    texel d holds the samples whose angle around c, from the +x axis, is below the angle of d;
//    the sector from v0 to v1 (counter-clockwise, less than pi) is then S(v1) & ~S(v0), or
//    S(v1) | ~S(v0) when it contains the +x axis;
//  * the line table, a 2D texture (default 512x512) indexed by the foot f of the perpendicular
//    from c to the segment's line, over [-R, R]^2: texel f holds the samples beyond that line,
//    s . f > f . f (all samples for the texels around c, where the sector alone decides, as the
//    paper says). R is the largest sample radius, so feet outside hold no sample.
// M = sector & line. Both tables are built in the light's normalised frame (the unit square of
// a rect light, the unit disc of a disk light): the covered relation is affine-invariant, so a
// table depends on the sample pattern only, not on the light's size. Sphere lights (samples in
// a ball) have no such table; dcs uses the exact test for them.
// Packed positions (7.1): each sample's normalised position quantised to 8 bits per coordinate,
// two samples per 32-bit word, the input of the `naive` mode.
//
// File format (luts/*.lut; the header is core/table_file.h's, which every table file shares): a text header of `key
// value` lines, then the tables as little-endian uint32 words:
//   penumbra-edge-lut 2
//   samples N / sets S / words W (ceil(N / 32)) / cube C / line L / extent R (%.9g)
//   pattern <16 hex digits>   FNV-1a 64 of N, S and the normalised positions' float bits
//   checksum <16 hex digits>  FNV-1a 64 of the lines above (each with its newline), then the
//                             payload bytes (format 1 left the header out: an edited extent
//                             passed; it is refused, to be regenerated)
//   end
// payload: sector [S][6][C][C][W] (faces in GL order +X -X +Y -Y +Z -Z, rows by t), line
// [S][L][L][W] (rows by y), packed positions [S][ceil(N / 2)].
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "sampling/light_samples.h"

namespace penumbra::dcs {

// Rect and disk lights: the lights a table can serve.
bool edgeLutSupports(const Light& light);

// The samples of every set in the light's normalised frame, ((x - c) . t / hx, (x - c) . b / hy)
// with hx, hy the half-size (rect) or the radius (disk), [set * count + k]. Computed from the
// samples' light coordinates (2 uv - 1), not their world positions, so that a pattern gives the
// same bits on a light of any size and place. Rect and disk sets only.
std::vector<glm::vec2> normalisedSamples(const LightSampleSet& samples);

// A light whose world frame is the normalised frame (a 2 x 2 rect or a unit disk at the
// origin, facing -y): `penumbra lut` builds tables for a pattern on it when no scene is given.
Light unitLight(LightShape shape);

// 32-bit words of packed positions per set: two samples a word.
inline int packedWords(int samples) { return (samples + 1) / 2; }

struct EdgeLutSize {
  int cube = 64;   // sector table: cube x cube texels per face
  int line = 512;  // line table: line x line texels
};

struct EdgeLut {
  int samples = 0, sets = 0, words = 0;
  EdgeLutSize size;
  float extent = 0.0f;        // R: the line table covers feet in [-R, R]^2
  std::uint64_t pattern = 0;  // patternHash of the positions it was built for
  std::vector<std::uint32_t> sector, line, packed;
};

std::uint64_t patternHash(const std::vector<glm::vec2>& normalised, int samples, int sets);

// Builds the tables for `sets` sets of `samples` normalised positions (1..128 samples).
EdgeLut buildEdgeLut(const std::vector<glm::vec2>& normalised, int samples, int sets, const EdgeLutSize& size = {});

// The sample a packed word holds: its normalised position as the `naive` mode decodes it.
glm::vec2 unpackPosition(const EdgeLut& lut, int set, int k);

// The file name a pattern's table has in luts/: edge_<shape>_<strategy>_<pattern>_n<N>_seed<S>.lut
// (plus _k<K> or _m<M> for interleaved or decorrelated patterns).
std::string edgeLutFileName(const LightSampleSet& samples);

// Throws penumbra::Error(path, ...) on an unwritable path.
void writeEdgeLut(const std::string& path, const EdgeLut& lut);
// Throws penumbra::Error(path, ...) for a missing, truncated or corrupt file (bad header, size or
// checksum).
EdgeLut readEdgeLut(const std::string& path);
// Throws penumbra::Error(path, ...) unless `lut` was built for this pattern (the renderer refuses
// a table of another sample pattern).
void checkEdgeLutMatches(const EdgeLut& lut, const std::string& path, const std::vector<glm::vec2>& normalised,
                         int samples, int sets);

}  // namespace penumbra::dcs
