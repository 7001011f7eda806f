// kit::WarpedFaceMaps' depth pass (kit/warped_faces.h): layered_depth.vert's, with the casters
// clipped to the light's side of the face and to the warp's side of its centre (both w > 0:
// warped_faces_shared.h says why). The face's matrix is the depth block's, as for any map.
#include "common.glsl"
#include "shadowlab/kit/depth_map_shared.h"
#include "shadowlab/kit/layered_depth_shared.h"
#include "shadowlab/kit/warped_faces_shared.h"

layout(location = 0) in vec3 inPosition;

out float vLinearDepth;

void main() {
    vec4 world = uModel * vec4(inPosition, 1.0);
    vLinearDepth = dot(uLinearDepthPlane, world);
    gl_ClipDistance[0] = dot(uFaceClipPlanes[0], world);
    gl_ClipDistance[1] = dot(uFaceClipPlanes[1], world);
    gl_Position = uShadowMatrix * world;
}
