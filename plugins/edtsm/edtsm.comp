// edtsm's compute passes (edtsm.cpp, docs/anti-aliased-edges.md). The seed pass (uEdtStep = 0)
// marks the map's depth edges: a texel with a 4-neighbour more than uEdtEdgeDepth world units
// farther from the light is a caster-edge site (the occluding side of a silhouette), one with a
// neighbour that much nearer a background-edge site (the side a receiver behind the caster sees
// lit). Each later pass is one round of jump flooding (Rong and Tan 2006): every texel keeps, of
// its own and its 8 neighbours' (uEdtStep texels away) nearest sites of each kind, the nearest to
// its own centre; steps halving to 1 and one more at 1 leave each texel within the flood's reach
// with (nearly always) its nearest site of each kind: a discrete Euclidean distance transform.
#include "shadowlab/kit/depth_map_shared.h"
#include "light_depth.glsl"
#include "edtsm_shared.h"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = kDepthMapUnit) uniform sampler2D uEdtDepth;
layout(binding = kEdtSitesUnit) uniform sampler2D uEdtSource;
layout(binding = kEdtSitesImageUnit, rgba32f) uniform writeonly image2D uEdtSites;

float edtDepthAt(ivec2 t, int last) {
    return lightLinearDepth(texelFetch(uEdtDepth, clamp(t, ivec2(0), ivec2(last)), 0).r, uLightDepth);
}

vec4 edtSeed(ivec2 q, int last) {
    const ivec2 kSides[4] = ivec2[4](ivec2(-1, 0), ivec2(1, 0), ivec2(0, -1), ivec2(0, 1));
    float d = edtDepthAt(q, last);
    bool caster = false, background = false;
    for (int k = 0; k < 4; ++k) {
        float dn = edtDepthAt(q + kSides[k], last);
        caster = caster || dn - d > uEdtEdgeDepth;
        background = background || d - dn > uEdtEdgeDepth;
    }
    vec2 self = vec2(q);
    return vec4(caster ? self : vec2(kEdtNoSite), background ? self : vec2(kEdtNoSite));
}

// Squared distance from q to a site (huge for none).
float edtDistance2(vec2 site, ivec2 q) {
    vec2 d = site - vec2(q);
    return dot(d, d);
}

vec4 edtJump(ivec2 q, int last) {
    vec4 best = texelFetch(uEdtSource, q, 0);
    for (int y = -1; y <= 1; ++y)
        for (int x = -1; x <= 1; ++x) {
            ivec2 t = q + ivec2(x, y) * uEdtStep;
            if ((x == 0 && y == 0) || any(lessThan(t, ivec2(0))) || any(greaterThan(t, ivec2(last)))) continue;
            vec4 other = texelFetch(uEdtSource, t, 0);
            if (edtDistance2(other.xy, q) < edtDistance2(best.xy, q)) best.xy = other.xy;
            if (edtDistance2(other.zw, q) < edtDistance2(best.zw, q)) best.zw = other.zw;
        }
    return best;
}

void main() {
    int last = int(uLightDepth.w) - 1;
    ivec2 q = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThan(q, ivec2(last)))) return;
    imageStore(uEdtSites, q, uEdtStep == 0 ? edtSeed(q, last) : edtJump(q, last));
}
