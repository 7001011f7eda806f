// Shadow volumes: one fragment of a volume face. The count itself is the stencil's; the debug
// passes add a constant (overdraw: 1/16 a fragment, saturating at 16) or mark an edge.
#include "shadow_volumes_shared.h"

layout(location = 0) out vec4 outColor;
layout(location = kIncrementLocation) uniform float uIncrement;

void main() {
    outColor = vec4(uIncrement);
}
