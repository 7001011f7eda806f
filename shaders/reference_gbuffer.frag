// Reference G-buffer: position (w = 1 where geometry was drawn) and the normal facing the viewer.
in vec3 vWorldPos;
in vec3 vWorldNormal;

layout(location = 0) out vec4 outPosition;
layout(location = 1) out vec4 outNormal;

void main() {
    vec3 n = normalize(vWorldNormal);
    outPosition = vec4(vWorldPos, 1.0);
    outNormal = vec4(gl_FrontFacing ? n : -n, 0.0);
}
