// One point per potential silhouette edge; the geometry shader builds its wedge solid.
layout(location = 0) in int inEdge;
flat out int vEdge;
void main() { vEdge = inEdge; }
