// Planar shadows, pass 2: a caster flattened onto the receiver plane (seed 000 eq. 3.3,
// generalised: M = dot(P, L) I - L P^T, see planar_projection.h).
#include "common.glsl"

layout(location = 0) in vec3 inPosition;
#include "planar_shared.h"

out float gl_ClipDistance[2];

void main() {
    vec4 world = uModel * vec4(inPosition, 1.0);
    float heightAbovePlane = dot(uPlane, world);
    float lightHeight = dot(uPlane, uLight);
    // Parts below the receiver cast nothing onto its lit side, and geometry lying in the receiver's
    // plane (the receiver itself) would cover all of it: both are clipped. The margin is far
    // below any caster's thickness and far above float error at scene scale.
    gl_ClipDistance[0] = heightAbovePlane - 1e-4;
    // Parts at or above a point light's height would project through the light (the divide by
    // lightHeight - heightAbovePlane flips sign): the anti-shadow of seed 000 Fig. 3.3.
    bool local = uLight.w != 0.0;
    gl_ClipDistance[1] = (local && uClipAntiShadow != 0) ? (lightHeight - heightAbovePlane) - 1e-4 * abs(lightHeight) : 1.0;
    gl_Position = uViewProjection * (uPlanarProjection * world);
}
