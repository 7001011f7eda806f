// Linear depth (seed 002 sec. 5.3): written per fragment, since interpolating it as z/w across a
// warped triangle would bend it; polygon offset does not apply to a written depth, so eq. 5.2's
// slope-scaled bias (factor * depth slope + r * units) is added here. Peeling (sec. 5.2): the
// second layer keeps only fragments behind the first layer's depth at the same texel.
#include "shadowlab/kit/layered_depth_shared.h"

layout(binding = kFirstDepthUnit) uniform sampler2D uFirstLayer;

in float vLinearDepth;

void main() {
    // Depth clamp is on: store what the fixed-function path would, clamped to [0, 1], and bias it
    // here (kit/layered_depth.h says why not with glPolygonOffset): the slope-scaled part from the depth's
    // own screen derivatives (eq. 5.2), the constant part in units of 2^-24.
    float depth = uLinearDepth == 1 ? vLinearDepth : gl_FragCoord.z;
    float slope = max(abs(dFdx(depth)), abs(dFdy(depth)));
    depth = clamp(depth, 0.0, 1.0) + uSlopeFactor * slope + uConstantUnits * exp2(-24.0);
    // Same program, same depth for the same surface in both layers: a strict comparison peels it
    // (with the stored value's rounding allowed for in a 16- or 24-bit map).
    if (uPeel == 1 && depth <= texelFetch(uFirstLayer, ivec2(gl_FragCoord.xy), 0).r + uPeelTolerance) discard;
    gl_FragDepth = depth;
}
