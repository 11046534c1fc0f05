// Shadow-volume input: world position (xyz) and the volume weight (w) of the edge or cap.
layout(location = 0) in vec4 inPositionWeight;
out vec4 vPositionWeight;
void main() { vPositionWeight = inPositionWeight; }
