// area-reference, one light sample: binary visibility of each pixel's surface point in this
// sample's shadow map, added to the accumulation target by the blend unit (GL_CONSTANT_COLOR =
// 1/N times the source plus the destination), so after N samples it holds their average.
#include "common.glsl"
#include "light_space.glsl"
#include "shadowlab/kit/depth_map_shared.h"   // uShadowMatrix: this sample's light
#include "area_reference_shared.h"

layout(binding = kPositionsUnit) uniform sampler2D uPositions;
layout(binding = kSampleMapUnit) uniform sampler2DShadow uSampleShadowMap;

layout(location = 0) out float outVisible;

void main() {
    vec4 position = texelFetch(uPositions, ivec2(gl_FragCoord.xy), 0);
    if (position.w < 0.5) {
        outVisible = 0.0;
        return;
    }
    vec3 coord = shadowMapCoord(uShadowMatrix, position.xyz);
    // Outside this sample's map nothing was rendered that could occlude: lit.
    outVisible = insideShadowMap(coord) ? texture(uSampleShadowMap, coord) : 1.0;
}
