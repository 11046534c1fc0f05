// The plane through an edge (v0, v1) and a point x, shared by the shadow-volume count
// (hardsv_volume.frag: which side of a volume side the visible point is on) and the dcs wedges
// (dcs_wedge.frag: on which side of plane(p, e) the light centre lies, which chooses the sign
// of the edge's update). Both are the sign of the same determinant det(v0 - x, v1 - v0, c - x),
// and both shaders evaluate it through this one function, `precise` (no contraction into fused
// multiply-adds that the compiler might choose differently in the two shaders), so that for a
// point within rounding of a side plane the integration constant D(c) and the wedge updates
// agree on the side: D(s) = D(c) + sum of updates is then right on the centre's hard-shadow
// boundary too. n_e is written with the short edge vector v1 - v0 (accurate for edges seen
// end-on, common_dcs.glsl).
float edgePlaneDistance(vec3 v0, vec3 v1, vec3 c, vec3 x, out vec3 ne) {
  precise vec3 n = cross(v0 - x, v1 - v0);
  precise float d = dot(n, c - x);
  ne = n;
  return d;
}

// +1 when c lies on the side of plane(x, e) that n_e points to (or on it), else -1. For fixed
// c and e this is affine in x: comparing two points x says whether they lie on the same side of
// plane(c, e).
int sideOfEdgePlane(vec3 v0, vec3 v1, vec3 c, vec3 x) {
  vec3 ne;
  return edgePlaneDistance(v0, v1, c, x, ne) >= 0.0 ? 1 : -1;
}
