in vec3 vColour;
out vec4 outColor;

void main() { outColor = vec4(vColour, 1.0); }
