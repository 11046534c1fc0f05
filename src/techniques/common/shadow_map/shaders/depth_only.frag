// Depth-only passes (multi-view depth maps, the reproject central map): the depth test writes.
void main() {}
