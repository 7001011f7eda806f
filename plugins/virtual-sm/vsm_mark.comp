// Page marking (virtual shadow maps' "page flagging"; StratusGFX vsm_analyze_depth.cs, EEVEE Next
// shadow tile tagging): every pixel of the camera pre-pass marks the pages its shadow lookup will
// read: at the level of its screen footprint, every page within the PCF margin of its point.
#include "virtual_sm_pages.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = kPrepassPositionUnit) uniform sampler2D uPrepassPosition;   // xyz world, w = 1 where drawn
layout(binding = kPrepassNormalUnit) uniform sampler2D uPrepassNormal;
layout(std430, binding = VSM_REQUEST_BINDING) writeonly buffer Requests { uint uRequest[]; };
layout(rgba8, binding = kLevelImageUnit) uniform writeonly image2D uLevelImage;
layout(location = 16) uniform int uWriteLevelImage;

void main() {
    ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(texel, textureSize(uPrepassPosition, 0)))) return;
    vec4 position = texelFetch(uPrepassPosition, texel, 0);
    int level = -1;
    if (position.w > 0.5) {
        float viewDepth = -(uView * vec4(position.xyz, 1.0)).z;
        vec3 normal = texelFetch(uPrepassNormal, texel, 0).xyz;
        int footprintLevel = vsmFootprintLevel(viewDepth);
        // The point shadowTerm() looks up: offset along the normal by the level's texels.
        vec3 p = position.xyz + normal * (uVsmDepth.z * uLevel[footprintLevel].w);
        vec2 xy = vsmLightSpace(p).xy;
        level = vsmLevelFor(viewDepth, xy);
        if (level >= 0) {
            float margin = VSM_MARK_MARGIN_TEXELS * uLevel[level].w;
            ivec2 lo = ivec2(floor((xy - margin) / uLevel[level].z));
            ivec2 hi = ivec2(floor((xy + margin) / uLevel[level].z));
            for (int y = lo.y; y <= hi.y; ++y)
                for (int x = lo.x; x <= hi.x; ++x) uRequest[vsmEntry(level, ivec2(x, y))] = 1u;
        }
    }
    if (uWriteLevelImage != 0)
        imageStore(uLevelImage, texel, level < 0 ? vec4(0.0) : vec4(vsmLevelColour(level), 1.0));
}
