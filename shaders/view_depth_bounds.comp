// Sample distribution shadow maps (Lauritzen, Salvi and Lefohn 2011; Lauritzen 2010, "Sample
// distribution shadow maps", SIGGRAPH course): the nearest and farthest view depth of what the
// camera sees, reduced from the depth of the host's camera pre-pass (the depth-only pass is
// enough: view depth from window depth through the projection). One texel per invocation, a 16 x 16 tile
// reduced in shared memory, then one atomic per tile into the frame's slot of the ring. kit::ViewDepthBounds dispatches it
// (csm's fit = sdsm; lispsm's and tsm's range = receivers: kit/receiver_range.h).
#include "shadowlab/frame_block.h"
#include "shadowlab/kit/csm_shared.h"

layout(local_size_x = 16, local_size_y = 16) in;
layout(binding = kPrepassDepthUnit) uniform sampler2D uPrepassDepth;   // window depth, 1 where nothing was drawn
layout(std430, binding = CSM_DEPTH_BOUNDS_BINDING) buffer DepthBounds {
    uint uMinDepthBits;
    uint uMaxDepthBitsInverted;   // ~bits of the max, so one atomicMin and one clear value serve both
};

shared uint sMin;
shared uint sMaxInverted;

void main() {
    if (gl_LocalInvocationIndex == 0u) {
        sMin = 0xFFFFFFFFu;
        sMaxInverted = 0xFFFFFFFFu;
    }
    barrier();
    ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
    if (all(lessThan(texel, textureSize(uPrepassDepth, 0)))) {
        float window = texelFetch(uPrepassDepth, texel, 0).r;
        // NDC z = (P22 z + P32) / (P23 z + P33) solved for the eye-space z (perspective or
        // orthographic projection alike); the view depth is -z.
        float ndc = 2.0 * window - 1.0;
        float depth = -(uProjection[3][2] - ndc * uProjection[3][3]) / (ndc * uProjection[2][3] - uProjection[2][2]);
        if (window < 1.0 && depth > 0.0) {
            uint bits = floatBitsToUint(depth);
            atomicMin(sMin, bits);
            atomicMin(sMaxInverted, ~bits);
        }
    }
    barrier();
    if (gl_LocalInvocationIndex == 0u) {
        atomicMin(uMinDepthBits, sMin);
        atomicMin(uMaxDepthBitsInverted, sMaxInverted);
    }
}
