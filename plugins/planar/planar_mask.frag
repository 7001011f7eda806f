// Planar shadows: the flattened caster marks its pixels as shadowed, on the pixels where its
// receiving plane is the visible surface (the receiver test: the classic method's stencil, here
// the camera pre-pass's object id).
#include "planar_shared.h"

layout(binding = kObjectIdUnit) uniform usampler2D uObjectIds;
layout(location = 0) out float outMask;

void main() {
    if (uReceiverId != 0u && texelFetch(uObjectIds, ivec2(gl_FragCoord.xy), 0).r != uReceiverId) discard;
    outMask = 0.0;
}
