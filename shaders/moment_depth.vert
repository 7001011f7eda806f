// Moment map pass of the filterable shadow maps (vsm, esm, evsm, msm): rasterise the casters
// from the light and hand the fragment stage the linear light depth it turns into moments
// (convention in moment_shadows.glsl).
#define MOMENT_DEPTH_PASS 1
#include "common.glsl"
#include "moment_shadows.glsl"

layout(location = 0) in vec3 inPosition;
layout(location = 2) in vec2 inUv;

out float vLightDepth;
out vec2 vUv;   // for fragment stages that sample the material's textures (surfaceTransmission)

void main() {
    vUv = inUv;
    vec4 world = uModel * vec4(inPosition, 1.0);
    gl_Position = uShadowMatrix * world;
    vLightDepth = linearLightDepth(world.xyz);
}
