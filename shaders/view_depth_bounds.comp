// Sample distribution shadow maps (Lauritzen, Salvi and Lefohn 2011; Lauritzen 2010, "Sample
// distribution shadow maps", SIGGRAPH course): the nearest and farthest view depth of what the
// camera sees, reduced from the host's camera pre-pass. One texel per invocation, a 16 x 16 tile
// reduced in shared memory, then one atomic per tile into the frame's slot of the ring. kit::ViewDepthBounds dispatches it
// (csm's fit = sdsm; lispsm's and tsm's range = receivers: kit/receiver_range.h).
#include "shadowlab/frame_block.h"
#include "shadowlab/kit/csm_shared.h"

layout(local_size_x = 16, local_size_y = 16) in;
layout(binding = kPrepassPositionUnit) uniform sampler2D uPrepassPosition;   // xyz world, w = 1 where drawn
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
    if (all(lessThan(texel, textureSize(uPrepassPosition, 0)))) {
        vec4 position = texelFetch(uPrepassPosition, texel, 0);
        float depth = -(uView * vec4(position.xyz, 1.0)).z;
        if (position.w > 0.5 && depth > 0.0) {
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
