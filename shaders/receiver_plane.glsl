// Receiver-plane depth (Isidoro 2006, "Shadow mapping: GPU-based tips and techniques"): the
// receiver's map depth as a plane over the map, from screen-space derivatives, so that a test at a
// texel some way off compares that texel with the receiver's depth THERE rather than at the pixel
// (rbsm walks up to dozens of texels along an edge; on a receiver tilted to the light the plain
// depth would meet its own surface within a few texels and see an edge that is not there).
#ifndef SHADOWLAB_RECEIVER_PLANE_GLSL
#define SHADOWLAB_RECEIVER_PLANE_GLSL

// d(depth) / d(texel) along the map's x and y for `mapPos` = (position in texels, depth); zero
// where the pixel's footprint in the map is degenerate. Call in uniform control flow (derivatives).
vec2 receiverPlaneGradient(vec3 mapPos) {
    vec3 dx = dFdx(mapPos), dy = dFdy(mapPos);
    mat2 jacobian = mat2(dx.xy, dy.xy);   // screen -> texels, one column per screen axis
    float det = determinant(jacobian);
    if (abs(det) < 1e-8) return vec2(0.0);
    return vec2(dx.z, dy.z) * inverse(jacobian);
}

#endif
