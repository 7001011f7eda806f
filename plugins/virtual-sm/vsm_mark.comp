// Page marking (virtual shadow maps' "page flagging"; StratusGFX vsm_analyze_depth.cs, EEVEE Next
// shadow tile tagging): every pixel of the camera's depth-only pre-pass marks the pages its
// shadow lookup will read: at the level of its screen footprint, every page within the PCF margin
// of its point. The world position is rebuilt from depth through the inverse view-projection
// (as kit::ViewDepthBounds reads depth alone): the full pre-pass's position, normal and id
// targets cost 4-5 ms at 1080p on the H200, the depth-only one about 1.
#include "virtual_sm_pages.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = kPrepassDepthUnit) uniform sampler2D uPrepassDepth;   // window depth, 1 where nothing was drawn
layout(std430, binding = VSM_REQUEST_BINDING) writeonly buffer Requests { uint uRequest[]; };
layout(rgba8, binding = kLevelImageUnit) uniform writeonly image2D uLevelImage;
layout(location = 16) uniform int uWriteLevelImage;
layout(location = 17) uniform mat4 uInverseViewProjection;

// Marks level L's pages within `margin` texels of xy, those inside its window only (a page outside
// it would wrap onto another page's slot).
void markPages(int level, vec2 xy, float margin) {
    ivec2 first = ivec2(uLevel[level].xy), last = first + uVsmSizes.y - 1;
    ivec2 lo = max(ivec2(floor((xy - margin * uLevel[level].w) / uLevel[level].z)), first);
    ivec2 hi = min(ivec2(floor((xy + margin * uLevel[level].w) / uLevel[level].z)), last);
    for (int y = lo.y; y <= hi.y; ++y)
        for (int x = lo.x; x <= hi.x; ++x) uRequest[vsmEntry(level, ivec2(x, y))] = 1u;
}

void main() {
    ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = textureSize(uPrepassDepth, 0);
    if (any(greaterThanEqual(texel, size))) return;
    float window = texelFetch(uPrepassDepth, texel, 0).r;
    int level = -1;
    if (window < 1.0) {
        vec3 ndc = vec3((vec2(texel) + 0.5) / vec2(size), window) * 2.0 - 1.0;
        vec4 world = uInverseViewProjection * vec4(ndc, 1.0);
        vec3 position = world.xyz / world.w;
        float viewDepth = -(uView * vec4(position, 1.0)).z;
        int footprintLevel = vsmFootprintLevel(viewDepth);
        // shadowTerm() looks up the point moved along its normal by `normal_offset` texels of the
        // footprint level; depth has no normal (one from depth differences is wrong at every
        // silhouette), so the margin widens by that offset instead: the looked-up point lies
        // within it in light space (an orthonormal basis) at any level >= the footprint's.
        float offset = uVsmDepth.z;
        vec2 xy = vsmLightSpace(position).xy;
        // shadowTerm()'s level is the first from the footprint's whose window holds the moved point
        // with the 2.5-texel margin: every level whose window may hold it is marked, up to the first
        // that surely does (its window holds the unmoved point with the widened margin).
        for (int l = footprintLevel; l < uVsmSizes.x; ++l) {
            if (vsmInWindow(l, xy, VSM_MARK_MARGIN_TEXELS - offset)) {
                markPages(l, xy, VSM_MARK_MARGIN_TEXELS + offset);
                if (level < 0) level = l;
            }
            if (vsmInWindow(l, xy, VSM_MARK_MARGIN_TEXELS + offset)) break;
        }
    }
    if (uWriteLevelImage != 0)
        imageStore(uLevelImage, texel, level < 0 ? vec4(0.0) : vec4(vsmLevelColour(level), 1.0));
}
