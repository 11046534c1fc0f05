// Constants and small functions shared by C++ and GLSL. Valid in both languages: only
// #define, uint arithmetic with the `u` suffix, and functions written in the common subset.
// C++ includes it through src/sampling/shared.hpp (which provides `uint`); the shader loader
// prepends it to every shader. Never copy a value from here into either language by hand.
#ifndef PENUMBRA_SHARED_H
#define PENUMBRA_SHARED_H

// Functions here are `inline` in C++ (the header is included by several translation units).
// PENUMBRA_PRECISE: GLSL `precise` (no fused multiply-adds the compiler may choose differently
// in two shaders), nothing in C++.
#ifdef __cplusplus
#define PENUMBRA_FN inline
#define PENUMBRA_PRECISE
#else
#define PENUMBRA_FN
#define PENUMBRA_PRECISE precise
#endif

// ---- G-buffer layout (pipeline) ------------------------------------------------------------
#define PENUMBRA_GBUF_POSITION 0   // RGBA32F: world position, w = 1 where a surface was hit
#define PENUMBRA_GBUF_NORMAL 1     // RGBA32F: world normal facing the camera, w = material id
#define PENUMBRA_GBUF_ALBEDO 2     // RGBA16F: base colour, a = opacity
#define PENUMBRA_GBUF_SHADING 3    // RGBA32F: shading normal (interpolated vertex normal), unit, on
                                   // the side of the normal above; a = 0
#define PENUMBRA_GBUF_MATERIAL 4   // RGBA16F: metallic, roughness, BRDF model (PENUMBRA_BRDF_*), 0

// ---- texture units -------------------------------------------------------------------------
// Those every technique shares. A technique's own binding points are in its header beside its
// shaders (dcs_bindings.h, shadow_map_bindings.h, single_view_bindings.h), which its shaders and
// its C++ include.
#define PENUMBRA_UNIT_GBUF_POSITION 0
#define PENUMBRA_UNIT_GBUF_NORMAL 1
#define PENUMBRA_UNIT_GBUF_ALBEDO 2
#define PENUMBRA_UNIT_VISIBILITY 3      // RGBA16F: RGB visibility (eq. 2), a = 1
#define PENUMBRA_UNIT_SAMPLE_VIS 4      // R16F 2D array: per-sample transmittance, one layer a sample
#define PENUMBRA_UNIT_MATERIAL_TEX 5
#define PENUMBRA_UNIT_COUNTER 6         // R32F: shadow-volume count (hard-sv, dcs)
#define PENUMBRA_UNIT_FILTER_SOURCE 11  // RGBA32F: input of the interleaved-sampling filter
#define PENUMBRA_UNIT_GBUF_SHADING 20
#define PENUMBRA_UNIT_GBUF_MATERIAL 21
#define PENUMBRA_UNIT_MATERIAL_MR_TEX 22 // glTF metallicRoughnessTexture (G roughness, B metallic)
#define PENUMBRA_UNIT_LTC 23            // RGBA32F 2D array: the LTC GGX table (luts/ltc_ggx.lut)
#define PENUMBRA_UNIT_LIGHT_PREFILTERED 24  // RGBA32F 2D array: a textured light's prefiltered emission
#define PENUMBRA_UNIT_UNSHADOWED 25     // RGBA32F: ratio-exact's unshadowed term of one light (CPU integral)
#define PENUMBRA_IMAGE_SAMPLE_VIS 0     // image unit of the per-sample visibility array

// ---- shader storage / uniform buffer bindings ----------------------------------------------
// A graphics program (vertex/geometry/fragment) that writes a storage block declares storage
// blocks in that one stage only (gl::Program refuses others): Mesa 22.3's GLSL linker computes
// each stage's write mask with the program-wide block index, so with blocks in two stages the
// writing stage's block can be marked read-only, and zink then neither waits for its writes
// before a glGetBufferSubData nor orders them before later reads, which glMemoryBarrier
// guarantees (GL 4.5 7.12.2, BUFFER_UPDATE and SHADER_STORAGE barrier bits). Counters that
// several stages write are images (their write access is given at bind time).
#define PENUMBRA_SSBO_LIGHT_SAMPLES 0   // vec4 position (xyz), per set then sample
#define PENUMBRA_SSBO_SAMPLE_RADIANCE 1 // vec4 normalised luminance L_i (rgb) of eq. 2
#define PENUMBRA_SSBO_VOLUME_FACES 8    // shadow-volume count (hard-sv, dcs): 3 vec4 a face (hardsv_volume.frag)
#define PENUMBRA_VSSM_FIXED_ONE 32767.0 // vssm exact SAT: depth in [0,1] as 15-bit integers (sums of
                                        // squares stay below 2^53 at 2048^2: exact in doubles)

// ---- light shapes (match penumbra::LightShape) ---------------------------------------------
#define PENUMBRA_LIGHT_POINT 0
#define PENUMBRA_LIGHT_RECT 1
#define PENUMBRA_LIGHT_DISK 2
#define PENUMBRA_LIGHT_SPHERE 3

// ---- pixel patterns of light-sample sets (match penumbra::PixelPattern) --------------------
#define PENUMBRA_PATTERN_CORRELATED 0
#define PENUMBRA_PATTERN_DECORRELATED 1
#define PENUMBRA_PATTERN_INTERLEAVED 2

// ---- limits --------------------------------------------------------------------------------
#define PENUMBRA_MAX_SAMPLES 128
#define PENUMBRA_DCS_MAX_TARGETS 7      // packed counter targets per pass (+1 checksum = 8 MRT)
#define PENUMBRA_MAP_LOCAL_SIZE 64      // threads per work group of the point reprojection

// Integer hash (PCG output permutation); identical in C++ and GLSL.
PENUMBRA_FN uint penumbraHash(uint v) {
  uint state = v * 747796405u + 2891336453u;
  uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}

// The light-sample set a pixel uses. Correlated: set 0 everywhere. Decorrelated: a hash of the
// pixel and seed picks one of `sets` rotated sets. Interleaved: the pixel's position in a K x K
// tile picks the set (sets == K*K).
PENUMBRA_FN uint penumbraSetForPixel(uint x, uint y, uint pattern, uint sets, uint k, uint seed) {
  if (pattern == uint(PENUMBRA_PATTERN_DECORRELATED))
    return penumbraHash(x ^ penumbraHash(y ^ penumbraHash(seed))) % sets;
  if (pattern == uint(PENUMBRA_PATTERN_INTERLEAVED)) return (y % k) * k + (x % k);
  return 0u;
}

// ---- dcs covered-sample modes (src/techniques/dcs/edge_lut.h) -------------------------------
#define PENUMBRA_DCS_COVERAGE_EXACT 0   // per-sample 3D test (common_dcs.glsl dcsCovered)
#define PENUMBRA_DCS_COVERAGE_NAIVE 1   // per-sample 2D test on 8-bit packed positions (paper 7.1)
#define PENUMBRA_DCS_COVERAGE_LUT 2     // sector & line bit fields from the edge LUT (paper 7.3)

// ---- dcs semi-opaque occluders (src/techniques/dcs/opacity.h) ------------------------------
#define PENUMBRA_DCS_OPACITY_OPAQUE 0   // one unit per occluder: visible iff the count is 0
#define PENUMBRA_DCS_OPACITY_SUM 1      // the paper's sum of opacities: T = 1 - Sat(count / Q)
#define PENUMBRA_DCS_OPACITY_PRODUCT 2  // units of -ln T: T = exp(-count * delta), 0 from U on

// Transmittance of a counter holding `count` units (negative counts read as 0); opaqueUnits is
// Q (sum) or U (product), unitLog is delta (product).
PENUMBRA_FN float penumbraDcsTransmittance(float count, int mode, float opaqueUnits, float unitLog) {
  float c = max(count, 0.0f);
  if (mode == PENUMBRA_DCS_OPACITY_SUM) return max(1.0f - c / opaqueUnits, 0.0f);
  if (mode == PENUMBRA_DCS_OPACITY_PRODUCT) return c >= opaqueUnits ? 0.0f : exp(-c * unitLog);
  return c > 0.0f ? 0.0f : 1.0f;
}

// How far off its surface visibility is evaluated for a point p, relative to p's own floating-
// point magnitude, never to the scene's size (Waechter and Binder, "A Fast and Robust Method for
// Avoiding Self-Intersection", Ray Tracing Gems 2019, ch. 6: an offset of 256 ULPs of the point's
// coordinates, a fixed tiny offset near the origin). We use the largest coordinate for all three
// axes (one distance along the view ray below, not one integer offset per axis) and keep their
// 256 ULPs = 2^-15 relative. Points are in camera-relative coordinates (Scene::cameraRelative),
// so the magnitude is the distance to the camera (at least zNear / sqrt 3 for a visible point)
// and a scene translated anywhere gives the same offset; a scaled scene gets a scaled offset, bit
// for bit at powers of two; a mirrored one the same (absolute values). Divergence: their fixed
// offset near the origin (magnitudes below 1/32 counted as 1/32, which we had) made a world in
// millimetres differ from the same world in metres (hard case 36: the cube scene at 2^-13 off at
// 30 of 4096 values, at 2^-20 at 207); near the camera a visible point cannot be, so the floor is
// 2^-100, there only to keep the offset positive at a CPU G-buffer's world origin.
#define PENUMBRA_EPS_RELATIVE (1.0f / 32768.0f)
#define PENUMBRA_EPS_ORIGIN 7.88860905e-31f  // 2^-100 (no hex floats in GLSL)
PENUMBRA_FN float penumbraSurfaceEpsilon(vec3 p) {
  float m = max(max(abs(p.x), abs(p.y)), max(abs(p.z), PENUMBRA_EPS_ORIGIN));
  return m * PENUMBRA_EPS_RELATIVE;
}

// Where visibility is evaluated for a visible point p (unit normal n facing the camera, camera
// at `eye`): p moved towards the camera along the view ray until it is penumbraSurfaceEpsilon(p)
// off its surface, at most PENUMBRA_ORIGIN_MAX_STRETCH times that along the ray (grazing views).
// The reference starts its shadow rays there, and the shadow-volume count and the dcs wedges
// evaluate their plane tests there: on the view ray, so that what the rasteriser found along
// that ray (which volume face the ray meets, near a face's border too) holds for the point (an
// origin moved along the normal instead left a pixel of hard case 19 off by one, where the ray
// passes within 1e-5 of the box's bottom edge). Without a camera (CPU-only G-buffers),
// eye = p + n.
#define PENUMBRA_ORIGIN_MAX_STRETCH 16.0f
PENUMBRA_FN vec3 penumbraShadowOrigin(vec3 p, vec3 n, vec3 eye) {
  PENUMBRA_PRECISE vec3 v = normalize(eye - p);
  PENUMBRA_PRECISE float along = penumbraSurfaceEpsilon(p) / max(dot(n, v), 1.0f / PENUMBRA_ORIGIN_MAX_STRETCH);
  PENUMBRA_PRECISE vec3 o = p + v * along;
  return o;
}

// ---- the shadow-volume count (techniques/shadow_volume) and dcs's wedges ------------------
#ifdef __cplusplus
#define PENUMBRA_INOUT(T) T&
#define PENUMBRA_OUT(T) T&
#else
#define PENUMBRA_INOUT(T) inout T
#define PENUMBRA_OUT(T) out T
#endif

PENUMBRA_FN float penumbraDet3(vec3 a, vec3 b, vec3 c) {
  PENUMBRA_PRECISE float r = dot(a, cross(b, c));
  return r;
}

// The plane through an edge (v0, v1) and a point x: the shadow-volume count (which side of a
// volume side the visible point lies on) and the dcs wedges (on which side of plane(p, e) the
// light centre lies, which chooses the sign of the edge's update) evaluate the sign of the same
// determinant det(v0 - x, v1 - v0, c - x) through this one function, precise, so that for a point
// within rounding of a side plane the integration constant D(c) and the wedge updates agree:
// D(s) = D(c) + sum of updates is then right on the centre's hard-shadow boundary too. n_e is
// written with the short edge vector v1 - v0 (accurate for edges seen end-on, common_dcs.glsl).
// Mathematically det(v0 - x, v1 - v0, c - x) = det(v0 - c, v1 - c, c - x).
PENUMBRA_FN float penumbraEdgePlaneDistance(vec3 v0, vec3 v1, vec3 c, vec3 x, PENUMBRA_OUT(vec3) ne) {
  PENUMBRA_PRECISE vec3 n = cross(v0 - x, v1 - v0);
  PENUMBRA_PRECISE float d = dot(n, c - x);
  ne = n;
  return d;
}

// +1 when c lies on the side of plane(x, e) that n_e points to (or on it), else -1.
PENUMBRA_FN int penumbraSideOfEdgePlane(vec3 v0, vec3 v1, vec3 c, vec3 x) {
  vec3 ne = vec3(0.0f);
  return penumbraEdgePlaneDistance(v0, v1, c, x, ne) >= 0.0f ? 1 : -1;
}

// Which faces of the shadow volumes the view ray meets (src/techniques/common/shadow_volume/shaders/hardsv_volume.frag). The count at
// a visible point o is the sum, over the volume faces the ray from the eye through o meets beyond
// o, of -w where the face is seen from its front and +w from its back (z-fail, Everitt and
// Kilgard 2002). Whether the ray meets a face is decided exactly here, not by the rasteriser:
// rasterisation snaps vertices to its sub-pixel grid, so near the line where two faces meet the
// face it gives a pixel to can be the wrong one. That is harmless while the two crossings lie on
// one side of o, but a view ray through the line from the light through a vertex (hard case 34)
// meets both faces there, near o, one before and one after it: the engine scene at 128 px had a
// pixel whose count was 11 where the volumes hold 13 (an edge-on side face rasterised across the
// line that the exact geometry kept it from).
//
// The line through o with direction d meets a convex polygon exactly when its Plücker products
// with the polygon's edges, taken around the polygon, all have one sign; that sign is +1 where
// the polygon is seen from its front (its normal by the right-hand rule faces the eye). The
// product with an edge P -> Q (homogeneous points, w = 0 at infinity) is
// det[P; Q; (o, 1); (d, 0)]. Each edge's product is computed by one function of the edge alone,
// with the edge put in a canonical order and the result negated for the other order, so the
// faces that share an edge (a side and its neighbour along a vertex line, a side and the cap
// along an occluder edge, a side and the far cap at infinity) take exactly opposite values and
// the ray meets exactly one of two faces folding apart there, or both or neither of two folded
// together: the volumes stay watertight whatever rounding does. A product of exactly 0 counts as
// +1 in the canonical order.
// The rasteriser only hands the fragment shader candidate pixels: each face is drawn grown on
// screen by a margin above the rasteriser's snapping (techniques/shadow_volume/volume_cover.h).
PENUMBRA_FN bool penumbraLexLess(vec3 a, vec3 b) {
  return a.x != b.x ? a.x < b.x : (a.y != b.y ? a.y < b.y : a.z < b.z);
}

// Edge a -> b between finite points: -det(a - o, b - o, d), written with the edge vector
// (-det(a - o, b - a, d)) so that its rounding is that of the point's distance, not its square.
// With the light centre c in place of o, the edge a_inf -> b_inf at infinity between the
// directions a - c and b - c: -det(a - c, b - c, d) = -det(a - c, b - a, d).
PENUMBRA_FN int penumbraViewEdgeSide(vec3 a, vec3 b, vec3 o, vec3 d) {
  bool swapped = penumbraLexLess(b, a);
  vec3 u = swapped ? b : a;
  vec3 v = swapped ? a : b;
  int s = -penumbraDet3(u - o, v - u, d) >= 0.0f ? 1 : -1;
  return swapped ? -s : s;
}

// The edge from a vertex v to infinity away from the light centre c (a vertex line): the product
// is (v - c) . n with n = cross(d, o - c), one vector per pixel, so it depends on v alone; the
// edge from infinity back to v has the opposite sign.
PENUMBRA_FN int penumbraViewVertexLineSide(vec3 v, vec3 c, vec3 n) {
  PENUMBRA_PRECISE float s = dot(v - c, n);
  return s >= 0.0f ? 1 : -1;
}

// What a side of edge (v0, v1) (in the edge's own order; weight w = m_e times the mesh's units,
// its sign turning the quad to face out of the volume) adds to the count at o: the quad
// b -> a -> a_inf -> b_inf with (a, b) = (v0, v1), swapped for w < 0. It lies beyond o where o
// and the ray's direction are on opposite sides of the side's plane (the plane through c): o's
// side is penumbraSideOfEdgePlane, the very decision dcs's wedges take for the sign of their
// update, and the direction's side is the product with the quad's edge at infinity.
PENUMBRA_FN float penumbraSideCount(vec3 v0, vec3 v1, float w, vec3 c, vec3 o, vec3 d, vec3 n) {
  vec3 a = w < 0.0f ? v1 : v0;
  vec3 b = w < 0.0f ? v0 : v1;
  int s = penumbraViewEdgeSide(b, a, o, d);
  if (penumbraViewVertexLineSide(a, c, n) != s || penumbraViewEdgeSide(a, b, c, d) != s ||
      -penumbraViewVertexLineSide(b, c, n) != s)
    return 0.0f;
  if (penumbraSideOfEdgePlane(v0, v1, c, o) != -penumbraViewEdgeSide(v0, v1, c, d)) return 0.0f;
  return s > 0 ? -abs(w) : abs(w);
}

// A near cap (the triangle x -> y -> z, turned to face the light) of weight w.
PENUMBRA_FN float penumbraNearCapCount(vec3 x, vec3 y, vec3 z, float w, vec3 o, vec3 d) {
  int s = penumbraViewEdgeSide(x, y, o, d);
  if (penumbraViewEdgeSide(y, z, o, d) != s || penumbraViewEdgeSide(z, x, o, d) != s) return 0.0f;
  // Beyond o: sign(n . (x - o)) = sign(n . d), and sign(n . d) = -s.
  PENUMBRA_PRECISE vec3 nt = cross(y - x, z - x);
  PENUMBRA_PRECISE float f = dot(nt, o - x);
  if ((f >= 0.0f ? 1 : -1) != s) return 0.0f;
  return s > 0 ? -w : w;
}

#define PENUMBRA_VOLUME_SIDE 0      // face kinds of the count's storage block
#define PENUMBRA_VOLUME_NEAR_CAP 1
#define PENUMBRA_VOLUME_FAR_CAP 2

// The far cap of the triangle x -> y -> z (x, y, z projected to infinity from c, the triangle
// reversed: x_inf -> z_inf -> y_inf), behind every point. The ray's direction d (not -d) lies
// in the cone of the triangle's directions where the common sign is that of det(x - c, y - c,
// z - c).
PENUMBRA_FN float penumbraFarCapCount(vec3 x, vec3 y, vec3 z, float w, vec3 c, vec3 d) {
  int s = penumbraViewEdgeSide(x, z, c, d);
  if (penumbraViewEdgeSide(z, y, c, d) != s || penumbraViewEdgeSide(y, x, c, d) != s) return 0.0f;
  float orientation = penumbraDet3(x - c, y - c, z - c);
  if (orientation == 0.0f || (orientation > 0.0f ? 1 : -1) != s) return 0.0f;
  return s > 0 ? -w : w;
}

// ---- the unshadowed term of the ratio estimator ----------------------
// atan2(y, x) for y >= 0, in [0, pi], to about 1e-7 relative: Cephes' atanf (S. Moshier), its
// range reduction by tan(pi/8) and tan(3 pi/8) and its polynomial. GLSL only asks atan for an
// absolute error of about 2^-11 and llvmpipe's gave the polygon formula 3e-4 relative errors
// where a far light's edge terms cancel; this one is the same on the CPU and every GL.
PENUMBRA_FN float penumbraAtan2(float y, float x) {
  float ax = abs(x);
  float base = 0.0f;
  float r = 0.0f;
  if (y > 2.414213562f * ax) {
    base = 1.5707963268f;
    r = -ax / y;
  } else if (y > 0.414213562f * ax) {
    base = 0.7853981634f;
    r = (y - ax) / (y + ax);
  } else if (ax > 0.0f) {
    r = y / ax;
  }
  float z = r * r;
  float a = base + ((((8.05374449538e-2f * z - 1.38776856032e-1f) * z + 1.99777106478e-1f) * z - 3.33329491539e-1f) * z * r + r);
  return x < 0.0f ? 3.1415926536f - a : a;
}

// ---- rect and disk lights as polygons seen from a point ------------------------------------
// Lambert's formula (Lambert 1760; in vector form Arvo 1995, "Applications of irradiance tensors
// to the simulation of non-Lambertian phenomena", eq. 8): for a polygon in z's hemisphere, the
// integral over its solid angle of the cosine with the unit z is 1/2 |sum_i E(v_i, v_i+1)|,
// E(u, v) = Theta (gamma . z) with Theta the angle between u and v and gamma the unit normal of
// the plane through the origin and that edge. Angles by atan2 (acos loses small ones). E is
// scale-invariant in each vertex (no normalize: an approximate inverse square root would cost
// more than the cancellation between the edges of a far polygon already does).
// The edge from u to u + e: its cross product as u x e, exact where e is (the light's edge
// vectors are made directly, not as differences of nearly equal vertices far from the light).
PENUMBRA_FN float penumbraEdgeIntegral(vec3 u, vec3 e, vec3 z) {
  vec3 c = cross(u, e);
  float s = length(c);
  return s > 0.0f ? penumbraAtan2(s, dot(u, u) + dot(u, e)) * (dot(c, z) / s) : 0.0f;
}

// The LTC frame's x: v's part orthogonal to ns (v along ns: the lobe is isotropic about ns, the
// t = 0 cells, any tangent serves); y = ns x x, z = ns.
PENUMBRA_FN vec3 penumbraLtcTangent(vec3 ns, vec3 v) {
  vec3 x = v - ns * dot(v, ns);
  if (!(length(x) > 1e-6f)) x = abs(ns.x) < 0.9f ? cross(ns, vec3(1.0f, 0.0f, 0.0f)) : cross(ns, vec3(0.0f, 1.0f, 0.0f));
  return normalize(x);
}

// w in the LTC frame (x, y, z), mapped by M^-1 = (a, c, b, d) (the LTC section below).
PENUMBRA_FN vec3 penumbraLtcMap(vec3 w, vec3 x, vec3 y, vec3 z, vec4 minv) {
  vec3 t = vec3(dot(w, x), dot(w, y), dot(w, z));
  return vec3(minv.x * t.x + minv.z * t.z, t.y, minv.y * t.x + minv.w * t.z);
}

// The light's polygon is clipped to half-spaces dot(plane_k, x) > 0 through the point, in order:
// 0 the geometric normal ng (the horizon rule every technique and the reference apply per sample,
// docs/architecture.md "Conventions"), 1 the shading normal ns (the cosine's max(., 0)), and for the LTC 2 the
// plane the transform maps to z = 0 (D_o's support). Clipping is streamed edge by edge (no vertex
// arrays, whose dynamic indexing made llvmpipe compile the shading shader for 80 s): an edge is
// cut by each plane in turn; where it leaves plane k's half-space the cut point is the clipped
// polygon's exit point on plane k, where it enters its entry point; once every edge is through,
// each plane's closing edge (exit -> entry, on the plane: the clipped polygon is convex, so one of
// each) is cut by the planes after it. Lambert's sum with z = ns takes the edges past planes 0-1,
// the LTC's (the edges mapped by M^-1 in the frame (x, y, ns), z = its z) those past plane 2.
struct PenumbraPolygonClip {
  vec3 plane[3];
  vec3 exitPoint[3];
  vec3 entryPoint[3];
  int crossings[3];  // bit 0: an exit point, bit 1: an entry point
  vec3 x, y;         // the LTC frame's tangents (z = plane[1] = ns)
  vec4 minv;         // (a, c, b, d) of M^-1 (the LTC section below)
  float lambert, ltc;
  int planes;        // 2: Lambert only, 3: also the LTC
};

// Edge (u, v) of the boundary (relative to the point) through planes first..planes-1; e = v - u,
// exact where it can be (penumbraEdgeIntegral). Each end is classified by dot(plane, end) of that
// very vector, the same value for the edges that share it (u + e would round differently: a cut
// point on plane 0 read as inside plane 1 at one edge's end and outside at the next edge's start
// lost the closing edge when ng = ns).
PENUMBRA_FN void penumbraClipEdge(PENUMBRA_INOUT(PenumbraPolygonClip) c, vec3 u, vec3 v, vec3 e, int first) {
  for (int k = 0; k < 3; ++k) {
    if (k == 2 && first <= 2) {
      c.lambert += penumbraEdgeIntegral(u, e, c.plane[1]);
      if (c.planes == 2) return;
    }
    if (k < first) continue;
    float hu = dot(c.plane[k], u), hv = dot(c.plane[k], v);
    if (!(hu > 0.0f) && !(hv > 0.0f)) return;
    if ((hu > 0.0f) != (hv > 0.0f)) {
      float t = hu / (hu - hv);
      vec3 cut = u + e * t;
      if (hu > 0.0f) {
        c.exitPoint[k] = cut;
        c.crossings[k] |= 1;
        v = cut;
        e = e * t;
      } else {
        c.entryPoint[k] = cut;
        c.crossings[k] |= 2;
        u = cut;
        e = e * (1.0f - t);
      }
    }
  }
  c.ltc += penumbraEdgeIntegral(penumbraLtcMap(u, c.x, c.y, c.plane[1], c.minv),
                                penumbraLtcMap(e, c.x, c.y, c.plane[1], c.minv), vec3(0.0f, 0.0f, 1.0f));
}

// A rect light (PENUMBRA_LIGHT_RECT: centre, unit tangent and bitangent, half extents `size`) or
// a disk light (PENUMBRA_LIGHT_DISK: radius size.x) seen from p, with geometric and shading
// normals ng and ns: (x) the irradiance of the light at radiance 1, the integral over it of
// cos(theta_p) cos(theta_l) / r^2 dA (m^2 / m^2: a form factor times pi), and, when withLtc, (y)
// the integral over it of the normalised LTC lobe for the view v and the table's M^-1 `minv`
// (the LTC section below). The disk is its equal-area regular 32-gon (radius scaled by
// sqrt((2 pi / 32) / sin(2 pi / 32)), so the polygon's area is the disk's): a disk has no
// elementary closed form off its axis (its vector irradiance is that of a circular current loop,
// elliptic integrals) and none once clipped; through Lambert's formula the 32-gon is within 3e-6
// relative of the disk while it is wholly above the horizon, 1.4e-4 where the horizon cuts it
// (tests/raytrace_analytic.cpp). The corners by rotating one (a rect's by
// pi / 2, the disk's by 2 pi / 32: no GL cos and sin). The emitter's one-sidedness is the
// caller's (a point behind the light's plane sees none of it).
PENUMBRA_FN vec2 penumbraLightPolygon(int shape, vec3 p, vec3 ng, vec3 ns, vec3 centre, vec3 tangent, vec3 bitangent,
                                      vec2 size, bool withLtc, vec3 v, vec4 minv) {
  PenumbraPolygonClip c;
  c.plane[0] = ng;
  c.plane[1] = ns;
  for (int k = 0; k < 3; ++k) {
    c.crossings[k] = 0;
    c.exitPoint[k] = vec3(0.0f);
    c.entryPoint[k] = vec3(0.0f);
  }
  c.lambert = 0.0f;
  c.ltc = 0.0f;
  c.planes = withLtc ? 3 : 2;
  c.minv = minv;
  // Plane 2: (M^-1 w).z > 0, i.e. w . (c x + d ns) > 0.
  c.x = penumbraLtcTangent(ns, v);
  c.y = cross(ns, c.x);
  c.plane[2] = c.x * minv.y + ns * minv.w;

  bool disk = shape == PENUMBRA_LIGHT_DISK;
  int n = disk ? 32 : 4;
  vec2 scale = disk ? vec2(size.x * 1.003222080f) : size;  // sqrt((pi / 16) / sin(pi / 16))
  vec2 rotation = disk ? vec2(0.980785280f, 0.195090322f) : vec2(0.0f, 1.0f);  // cos, sin of the step
  vec2 corner = disk ? vec2(1.0f, 0.0f) : vec2(-1.0f, -1.0f);
  vec3 base = centre - p;
  vec2 firstCorner = corner;
  vec3 first = base + tangent * (corner.x * scale.x) + bitangent * (corner.y * scale.y);
  vec3 u = first;
  for (int i = 0; i < n; ++i) {
    vec2 next = i == n - 1 ? firstCorner
                           : vec2(corner.x * rotation.x - corner.y * rotation.y, corner.y * rotation.x + corner.x * rotation.y);
    vec3 v = i == n - 1 ? first : base + tangent * (next.x * scale.x) + bitangent * (next.y * scale.y);
    vec3 e = tangent * ((next.x - corner.x) * scale.x) + bitangent * ((next.y - corner.y) * scale.y);
    penumbraClipEdge(c, u, v, e, 0);
    u = v;
    corner = next;
  }
  for (int k = 0; k < 3; ++k)
    if (c.crossings[k] == 3)
      penumbraClipEdge(c, c.exitPoint[k], c.entryPoint[k], c.entryPoint[k] - c.exitPoint[k], k + 1);
  return vec2(0.5f * abs(c.lambert), 0.5f * 0.31830988618f * abs(c.ltc));
}

PENUMBRA_FN float penumbraRectIrradiance(vec3 p, vec3 ng, vec3 ns, vec3 centre, vec3 tangent, vec3 bitangent,
                                         vec2 halfSize) {
  return penumbraLightPolygon(PENUMBRA_LIGHT_RECT, p, ng, ns, centre, tangent, bitangent, halfSize, false, ns,
                              vec4(1.0f, 0.0f, 0.0f, 1.0f)).x;
}

PENUMBRA_FN float penumbraDiskIrradiance(vec3 p, vec3 ng, vec3 ns, vec3 centre, vec3 tangent, vec3 bitangent,
                                         float radius) {
  return penumbraLightPolygon(PENUMBRA_LIGHT_DISK, p, ng, ns, centre, tangent, bitangent, vec2(radius), false, ns,
                              vec4(1.0f, 0.0f, 0.0f, 1.0f)).x;
}

// The cosine-weighted solid angle of a spherical cap of angular radius alpha (sin^2 alpha =
// sin2Alpha) whose axis makes the angle beta with the normal, clipped to the normal's hemisphere:
// pi sin^2(alpha) cos(beta) while the cap is wholly above the horizon, else Snyder's closed form
// for the cap crossing the horizon (J. Snyder 1996, "Area light sources for real-time graphics",
// MSR-TR-96-11; as in Lagarde and de Rousiers 2014, "Moving Frostbite to PBR", section 4.7.2):
// x = cot(alpha), y = -x cot(beta),
//   F = (cos(beta) acos(y) - x sin(beta) sqrt(1 - y^2)) sin^2(alpha) + atan(sin(beta) sqrt(1 - y^2) / x).
// Angles by penumbraAtan2 (GLSL's acos and atan are too coarse). Within 3.6e-6 of a 400 x 400
// quadrature over the cap (ClosedForms.CapCosineIsTheClippedIntegral).
PENUMBRA_FN float penumbraCapCosine(float cosBeta, float sin2Alpha) {
  if (cosBeta * cosBeta > sin2Alpha) return cosBeta > 0.0f ? 3.1415926536f * sin2Alpha * cosBeta : 0.0f;
  float sinBeta = sqrt(max(1.0f - cosBeta * cosBeta, 0.0f));
  float x = sqrt(max(1.0f / sin2Alpha - 1.0f, 0.0f));
  float y = sinBeta > 0.0f ? clamp(-x * cosBeta / sinBeta, -1.0f, 1.0f) : 0.0f;
  float sy = sqrt(max(1.0f - y * y, 0.0f));
  float acosY = penumbraAtan2(sy, y);
  float f = (cosBeta * acosY - x * sinBeta * sy) * sin2Alpha + penumbraAtan2(sinBeta * sy, x);
  return max(f, 0.0f);
}

// The same integral for a sphere light as penumbra models it (docs/architecture.md "Lighting pipeline": a
// ball of isotropic points, sampled in its volume, of total intensity L pi R^2). While the ball
// lies wholly above both the geometric and the shading normal's planes through p, the cosines
// need no clamping and the integral is the normal component of an inverse-square field, which
// for a uniform ball is that of its centre (Newton's shell theorem): pi R^2 cos(theta_s) / d^2.
// That is also the irradiance of a Lambertian sphere of radiance L seen fully above the horizon.
// Where the ball crosses the horizon, it is cut into shells about p: the
// shell of radius r meets the ball in a cap of angular radius alpha(r), cos(alpha) =
// (d^2 + r^2 - R^2) / (2 d r), and contributes the cap's clipped cosine integral
// (penumbraCapCosine) times the ball's intensity per volume, 3 / (4 R) of L: a 1D integral over
// r in [d - R, d + R], taken with r = d - R cos(t) by the midpoint rule in t on 32 points
// (spectrally accurate for this smooth integrand: in double 5e-6 relative at d >= 1.1 R, 2.4e-4
// at d = 1.001 R, against 20000 points; 1.7e-5 in float, tests/raytrace_analytic.cpp). One
// plane clips it: the shading normal's, when the ball is wholly above the geometric one's or the
// two normals agree (|ng - ns| <= 1e-5: a flat surface's interpolated normal). Returns -1
// otherwise, and for p inside the ball (the caller sums the samples).
PENUMBRA_FN float penumbraBallIrradiance(vec3 p, vec3 ng, vec3 ns, vec3 centre, float radius) {
  vec3 d = centre - p;
  float aboveS = dot(ns, d), aboveG = dot(ng, d);
  float d2 = dot(d, d);
  float dist = sqrt(d2);
  if (aboveS > radius && aboveG > radius) return 3.1415926536f * radius * radius * aboveS / (d2 * dist);
  if (!(dist > radius)) return -1.0f;
  if (!(aboveG > radius) && !(length(ng - ns) <= 1e-5f)) return -1.0f;
  float cosBeta = aboveS / dist;
  float sum = 0.0f;
  // cos(t) and sin(t) at t = (i + 1/2) pi / 32 by rotating by pi / 32 (no GL's cos and sin,
  // whose precision differs between drivers: the same numbers on the CPU and every GL).
  float c = 0.998795456f, sn = 0.049067674f;
  for (int i = 0; i < 32; ++i) {
    // 1 - cos(alpha) = (R^2 - (d - r)^2) / (2 d r) = R^2 sin^2(t) / (2 d r), as d - r = R cos(t):
    // sin^2(alpha) = u (2 - u) without the cancellation of 1 - cos^2(alpha) near the ends.
    float r = dist - radius * c;
    float u = radius * radius * sn * sn / (2.0f * dist * r);
    float sin2Alpha = min(u * (2.0f - u), 1.0f);
    if (sin2Alpha > 0.0f) sum += sn * penumbraCapCosine(cosBeta, sin2Alpha);
    float next = c * 0.995184727f - sn * 0.098017140f;
    sn = sn * 0.995184727f + c * 0.098017140f;
    c = next;
  }
  // 3 / (4 R) * R sin(t) dt summed with dt = pi / 32.
  return sum * (3.0f * 3.1415926536f / 128.0f);
}

// ---- a light sample's geometric term -----------------------------------------------------
// cos(theta_s) [cos(theta_l)] / r^2 of the light point x seen from p: 0 below the geometric
// normal ng's horizon (the horizon rule, docs/architecture.md "Conventions"), the cosine with the shading
// normal ns clamped at 0, [cos(theta_l)] only for a one-sided emitter (lightNormal its emission
// normal; 0 for isotropic lights, LightSampleSet::lightNormal). The pipeline's shading and the
// reference's shaded image both weight each sample by it.
PENUMBRA_FN float penumbraSampleGeometry(vec3 p, vec3 ng, vec3 ns, vec3 x, vec3 lightNormal) {
  vec3 d = x - p;
  if (!(dot(ng, d) > 0.0f)) return 0.0f;
  float r2 = dot(d, d);
  vec3 l = d / sqrt(r2);
  float emitter = dot(lightNormal, lightNormal) > 0.0f ? max(-dot(lightNormal, l), 0.0f) : 1.0f;
  return max(dot(ns, l), 0.0f) * emitter / r2;
}

// ---- BRDF -------------------------------------------------------------
// LAMBERT: albedo / pi (scene-file materials without "metallic"/"roughness", OBJ without Ks).
// METALLIC_ROUGHNESS: the glTF 2.0 specification's BRDF (Appendix B, "BRDF Implementation"):
//   c_diff = mix(baseColor, 0, metallic), f0 = mix(0.04, baseColor, metallic), alpha = roughness^2,
//   F = f0 + (1 - f0) (1 - |v.h|)^5 (Schlick), f = (1 - F) c_diff / pi + F D V,
//   D the GGX (Trowbridge-Reitz) distribution, V = G / (4 |n.l| |n.v|) with G the separable
//   Smith-GGX masking-shadowing (spec eq. for V_GGX).
// Divergence: roughness is clamped to >= PENUMBRA_MIN_ROUGHNESS (a mirror's D is a delta no
// light sample can hit; Filament clamps at the same value), and n.v to >= 1e-4 (a shading normal
// turned from the viewer: the lobe's limit, not a division by zero).
#define PENUMBRA_BRDF_LAMBERT 0
#define PENUMBRA_BRDF_METALLIC_ROUGHNESS 1
#define PENUMBRA_MIN_ROUGHNESS 0.045f

// GGX D(h) for alpha^2 = a2, nh = n.h (> 0).
PENUMBRA_FN float penumbraGgxD(float nh, float a2) {
  float d = nh * nh * (a2 - 1.0f) + 1.0f;
  return a2 / (3.1415926536f * d * d);
}

// The visibility term V = G / (4 n.l n.v) of the separable Smith-GGX G (glTF 2.0 Appendix B).
PENUMBRA_FN float penumbraGgxVisibility(float nl, float nv, float a2) {
  return 1.0f / ((nl + sqrt(a2 + (1.0f - a2) * nl * nl)) * (nv + sqrt(a2 + (1.0f - a2) * nv * nv)));
}

// The specular lobe without Fresnel, times the cosine: D V (n.l), for unit n, v, l. 0 below
// the horizon of n. What the LTC table fits (Heitz et al. 2016, section 4: BRDF * cos with F = 1).
PENUMBRA_FN float penumbraGgxCosine(vec3 n, vec3 v, vec3 l, float alpha) {
  float nl = dot(n, l);
  if (!(nl > 0.0f)) return 0.0f;
  float nv = max(dot(n, v), 1e-4f);
  vec3 h = v + l;
  float hl = length(h);
  if (!(hl > 0.0f)) return 0.0f;
  float nh = dot(n, h) / hl;
  if (!(nh > 0.0f)) return 0.0f;
  float a2 = alpha * alpha;
  return penumbraGgxD(nh, a2) * penumbraGgxVisibility(nl, nv, a2) * nl;
}

PENUMBRA_FN float penumbraAlpha(float roughness) {
  float r = max(roughness, PENUMBRA_MIN_ROUGHNESS);
  return r * r;
}

// Schlick's Fresnel for f0 at v.h.
PENUMBRA_FN vec3 penumbraSchlick(vec3 f0, float vh) {
  float m = 1.0f - max(vh, 0.0f);
  float m5 = m * m * m * m * m;
  return f0 + (vec3(1.0f) - f0) * m5;
}

// The BRDF f(v, l) = diffuse + specular (1/sr, rgb; the cosine not included) with shading
// normal n, unit v towards the viewer and l towards the light, in two parts: the ratio
// estimator gives each its own unshadowed term (Lambert's formula, LTC). Below n's horizon the
// specular part is 0 and the diffuse part keeps its value (the callers' cosine, clamped at 0,
// removes it).
PENUMBRA_FN vec3 penumbraF0(vec3 baseColor, float metallic) {
  return vec3(0.04f) * (1.0f - metallic) + baseColor * metallic;
}

PENUMBRA_FN vec3 penumbraFresnel(vec3 v, vec3 l, vec3 baseColor, float metallic) {
  vec3 f0 = penumbraF0(baseColor, metallic);
  vec3 h = v + l;
  float hl = length(h);
  return penumbraSchlick(f0, hl > 0.0f ? dot(v, h) / hl : 0.0f);
}

PENUMBRA_FN vec3 penumbraBrdfDiffuse(vec3 v, vec3 l, vec3 baseColor, float metallic, int model) {
  if (model != PENUMBRA_BRDF_METALLIC_ROUGHNESS) return baseColor * 0.31830988618f;
  return (vec3(1.0f) - penumbraFresnel(v, l, baseColor, metallic)) * baseColor * ((1.0f - metallic) * 0.31830988618f);
}

PENUMBRA_FN vec3 penumbraBrdfSpecular(vec3 n, vec3 v, vec3 l, vec3 baseColor, float metallic, float roughness,
                                      int model) {
  float nl = dot(n, l);
  if (model != PENUMBRA_BRDF_METALLIC_ROUGHNESS || !(nl > 0.0f)) return vec3(0.0f);
  return penumbraFresnel(v, l, baseColor, metallic) * (penumbraGgxCosine(n, v, l, penumbraAlpha(roughness)) / nl);
}

PENUMBRA_FN vec3 penumbraBrdf(vec3 n, vec3 v, vec3 l, vec3 baseColor, float metallic, float roughness, int model) {
  return penumbraBrdfDiffuse(v, l, baseColor, metallic, model) +
         penumbraBrdfSpecular(n, v, l, baseColor, metallic, roughness, model);
}


// ---- the GGX lobe's unshadowed integral over a polygon (LTC) --------------------------------
// Heitz, Dupuy, Hill and Neubelt 2016, "Real-time polygonal-light shading with linearly
// transformed cosines", section 5: the integral over a polygon of the lobe penumbraGgxCosine (F =
// 1) is norm times that of the clamped cosine D_o over the polygon transformed by M^-1, which is
// Lambert's formula / pi (penumbraLightPolygon's y). minv holds the table's (a, c, b, d) of
// M^-1 = [[a 0 b] [0 1 0] [c 0 d]] (src/shading/ltc.h) in the frame x = v's part orthogonal to
// ns, y = ns x x, z = ns. Divergence: the polygon is first clipped to the horizons of ng (the
// horizon rule) and of ns (the true lobe is 0 below it; the paper clips only the transformed
// polygon at z = 0, which we also do: D_o's support). Clipping commutes with the linear map, so
// the world planes clip before it. The caller multiplies by norm, Schlick's Fresnel at
// penumbraLtcFresnelDirection and the radiance.

// The table's texture coordinates (ltc.h grid: roughness, sqrt(1 - cos theta_v)) for a table of
// `size` cells a side, at texel centres.
PENUMBRA_FN vec2 penumbraLtcCoordinates(float roughness, float nv, float size) {
  vec2 g = vec2(clamp(roughness, 0.0f, 1.0f), sqrt(max(1.0f - clamp(nv, 0.0f, 1.0f), 0.0f)));
  return (g * (size - 1.0f) + vec2(0.5f)) / size;
}


// The direction at which the LTC's specular integral takes Schlick's Fresnel factor: towards the
// light's point nearest the mirror ray's hit on its plane (a rect's clamped to its extents, a
// disk's radially), moved towards the light's centre by min(2 alpha, 1) (the centre where the
// mirror ray does not meet the plane in front of p). Divergence from the paper's split (Hill
// 2016: norm and fresnel, the lobe's Schlick-weighted integral over the whole hemisphere, so
// F = f0 (norm - fresnel) + fresnel): at grazing views the hemisphere's average is the Fresnel of
// the lobe's grazing peak, not of the light's part of it, and a dielectric's specular term was
// 20-46% too high at roughness 0.3-0.7 (tests/shading_ltc_test.cpp; this: 2.5-6%, and 0.3% at
// roughness 0.05-0.1). A representative point as in Karis 2013 (section "Area lights"), with
// its distance to the centre our own heuristic, measured only on that test's floor.
PENUMBRA_FN vec3 penumbraLtcFresnelDirection(int shape, vec3 p, vec3 ns, vec3 v, vec3 centre, vec3 lightNormal,
                                             vec3 tangent, vec3 bitangent, vec2 size, float alpha) {
  vec3 m = ns * (2.0f * dot(ns, v)) - v;
  float towards = dot(m, lightNormal);
  vec3 q = centre;
  if (towards < -1e-4f) {  // unit vectors: the hit is at most 1e4 times p's distance to the plane
    vec3 hit = p + m * (dot(centre - p, lightNormal) / towards) - centre;
    vec2 uv = vec2(dot(hit, tangent), dot(hit, bitangent));
    if (shape == PENUMBRA_LIGHT_DISK) {
      float r = length(uv);
      if (r > size.x) uv = uv * (size.x / r);
    } else {
      uv = clamp(uv, -size, size);
    }
    q = centre + (tangent * uv.x + bitangent * uv.y) * (1.0f - min(2.0f * alpha, 1.0f));
  }
  return normalize(q - p);
}

// ---- textured rect and disk lights (Heitz et al. 2016, section 5.3) ------------------------
// The integral of a lobe D times the emission L over the light is taken as (integral of D) times
// L_D, the emission averaged with D's weight, and L_D is read from a chain of the emission
// texture prefiltered with Gaussians of growing width (src/shading/prefiltered_light.h) at the
// orthogonal projection of the shading point onto the light's plane after the lobe's M^-1 (the
// identity for the cosine lobe), with a footprint from that point's distance to the plane over
// the square root of the mapped uv square's area (the paper's heuristics; their demo's
// FetchDiffuseFilteredTexture). Divergences: the chain is a normalised convolution restricted to
// the light (defined on the margin around it, src/shading/prefiltered_light.h); and instead of
// one level at a log of the footprint, L_D mixes every level with the weights that make the
// mixture of Gaussians the clamped cosine's own footprint on a plane facing it,
// (1 + rho^2 / d^2)^-2 (penumbraPrefilterWeight): the cosine's heavy tail, which one Gaussian
// misses (tests/shading_prefilter_test.cpp: stained glass 1.5 above a floor, 0.038 -> 0.0058
// relative RMSE of the diffuse term).
#define PENUMBRA_PREFILTER_MARGIN 0.5f  // the chain covers uv in [-margin, 1 + margin]^2

// The light's uv square (u along the tangent from centre - tangent h.x - bitangent h.y at uv 0,
// v along the bitangent; a disk's is the square about it, as its samples' uv) seen from p,
// mapped by M^-1 in the LTC frame (x, y, z): vec3(u, v) of the projection of p onto the mapped
// plane, and d = its distance to p over the square root of the mapped square's area.
PENUMBRA_FN vec3 penumbraPrefilterFootprint(vec3 p, vec3 centre, vec3 tangent, vec3 bitangent, vec2 halfSize, vec3 x,
                                            vec3 y, vec3 z, vec4 minv) {
  vec3 o = penumbraLtcMap(centre - tangent * halfSize.x - bitangent * halfSize.y - p, x, y, z, minv);
  vec3 e1 = penumbraLtcMap(tangent * (2.0f * halfSize.x), x, y, z, minv);
  vec3 e2 = penumbraLtcMap(bitangent * (2.0f * halfSize.y), x, y, z, minv);
  vec3 n = cross(e1, e2);
  float area2 = dot(n, n), h = dot(n, o);
  vec3 r = n * (h / area2) - o;  // the foot point from the corner
  float a11 = dot(e1, e1), a12 = dot(e1, e2), a22 = dot(e2, e2), b1 = dot(r, e1), b2 = dot(r, e2);
  float det = a11 * a22 - a12 * a12;
  return vec3((b1 * a22 - b2 * a12) / det, (b2 * a11 - b1 * a12) / det, abs(h) / (sqrt(area2) * sqrt(sqrt(area2))));
}

// The share of chain level k (sigma_k = sigma0 2^k) in the cosine lobe's footprint at uv
// distance d: the lobe about the plane's normal weights the plane by (1 + rho^2 / d^2)^-2, which
// is the mixture over s of Gaussians of sigma^2 = d^2 / (2 s) with density e^-s (from
// integral_0^inf s e^(-s (1 + x)) ds = (1 + x)^-2); level k takes s in [s_k / 2, 2 s_k],
// s_k = d^2 / (2 sigma_k^2) (sigma within a factor sqrt 2 of sigma_k), level 0 all finer, the last
// level all coarser.
PENUMBRA_FN float penumbraPrefilterWeight(float d, float sigma0, int k, int levels) {
  float sigma = sigma0 * exp2(float(k));
  float s = d * d / (2.0f * sigma * sigma);
  float below = k == levels - 1 ? 1.0f : exp(-0.5f * s);  // e^-s at the bin's lower end in s (0: the coarsest level)
  float above = k == 0 ? 0.0f : exp(-2.0f * s);           // at its upper end (infinity: level 0)
  return below - above;
}

// The chain's texture coordinates of light uv.
PENUMBRA_FN vec2 penumbraPrefilterCoordinates(vec2 uv) {
  return (uv + vec2(PENUMBRA_PREFILTER_MARGIN)) / (1.0f + 2.0f * PENUMBRA_PREFILTER_MARGIN);
}


// ---- moment shadow maps (msm, msm-soft: src/techniques/msm) -------------------------------
// Peters and Klein 2015, "Moment shadow mapping", section 3.2 / Algorithm 2 (the Hamburger 4MSM):
// from the first four moments b = (E z, E z^2, E z^3, E z^4) of the depths in a filter region
// and a receiver depth zf, the distribution with the fewest points that matches b and has a
// point at zf (the bound's extremal one): its other points z2 < z3 are the roots of
// c1 + c2 z + c3 z^2, c = B^-1 (1, zf, zf^2), B the Hankel matrix [[1 b1 b2] [b1 b2 b3]
// [b2 b3 b4]] (solved by its LDL^T factorisation), and each point's weight is
// E[(Z - z_j)(Z - z_k)] / ((z_i - z_j)(z_i - z_k)) over the other two. Returns (G, D): G the
// weight of the points nearer than zf (the shadow intensity, 1 - visibility; the point at zf
// itself counts as lit, as the paper's), D their weighted depth sum (the moment soft shadows'
// blocker search, Peters, Muenstermann, Wetzstein and Klein 2016, section 5.1: the average
// blocker depth is D / G). b must be a moment vector with a positive definite B: the caller
// passes the moments of a standardised depth (mean 0, variance 1: B is then well conditioned in
// float), biased by penumbraMsmBias.
// The moment bias (Peters and Klein 2015, section 3.3: b' = (1 - alpha) b + alpha b*) on
// standardised moments (0, 1, skewness, kurtosis), towards those of the uniform distribution with
// the same mean and variance, (0, 1, 0, 9/5): B of a two-point distribution is singular (kurtosis
// = 1 + skewness^2); biased its last pivot is alpha (4/5 + skewness^2), relative to the moments'
// own spread, so the bias neither blurs a narrow cluster of depths (as a bias towards a fixed
// distribution over the whole depth range would) nor vanishes beside the float rounding of a
// skewed box's kurtosis. Divergence: the paper biases the raw moments towards a fixed vector.
PENUMBRA_FN vec4 penumbraMsmBias(float skewness, float kurtosis, float alpha) {
  return vec4(0.0f, 1.0f, (1.0f - alpha) * skewness, (1.0f - alpha) * kurtosis + alpha * 1.8f);
}

PENUMBRA_FN vec2 penumbraMsm4(vec4 b, float zf) {
  float d2 = b.y - b.x * b.x;                     // the LDL^T pivots of B
  float l32 = (b.z - b.x * b.y) / d2;
  float d3 = max(b.w - b.y * b.y - l32 * l32 * d2, 1e-20f);
  float y2 = zf - b.x, y3 = zf * zf - b.y - l32 * y2;
  float c3 = y3 / d3, c2 = y2 / d2 - l32 * c3;
  float c1 = 1.0f - b.x * c2 - b.y * c3;
  float mid = -0.5f * c2 / c3;
  float r = sqrt(max(mid * mid - c1 / c3, 0.0f));
  float z2 = mid - r, z3 = mid + r;
  // Weights of z2 and z3 (the one at zf is the rest).
  float w2 = (zf * z3 - b.x * (zf + z3) + b.y) / ((z2 - zf) * (z2 - z3));
  float w3 = (zf * z2 - b.x * (zf + z2) + b.y) / ((z3 - zf) * (z3 - z2));
  float g = 0.0f, depth = 0.0f;
  if (z2 < zf) {
    g += w2;
    depth += w2 * z2;
  }
  if (z3 < zf) {
    g += w3;
    depth += w3 * z3;
  }
  return vec2(clamp(g, 0.0f, 1.0f), depth);
}

#endif
