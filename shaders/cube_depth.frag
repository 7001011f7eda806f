// The kit's cube depth map: the linear distance to the light over the far distance, stored as
// the depth (so the main pass compares distances, the same in every direction of the cube). The
// depth written by a fragment stage gets no glPolygonOffset, so the same offset is applied here:
// factor * m + units * r, m the largest slope of the stored depth per texel, r = 2^-24 (the step
// of 24-bit and 32F depth near 1: glPolygonOffset's units for those formats).
#include "shadowlab/kit/cube_depth_map_shared.h"

in vec3 gWorldPos;

void main() {
    float depth = distance(gWorldPos, uCubeLight.xyz) / uCubeLight.w;
    float slope = max(abs(dFdx(depth)), abs(dFdy(depth)));
    gl_FragDepth = clamp(depth + uCubeBias.x * slope + uCubeBias.y * exp2(-24.0), 0.0, 1.0);
}
