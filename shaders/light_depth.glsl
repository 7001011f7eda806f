// Depth in light space, shared by the kernel-filtered techniques (disc_sampling.glsl: pcf,
// adaptive-pcf, pcss; and stochastic-sm, cssm2): linear depth from a stored depth, and the
// receiver's depth slope per texel that the cone bias scales. `lightDepth` is (near, far,
// 1 perspective / 0 orthographic, map resolution) and `worldSize` the map's extent in world units
// (orthographic) or at unit distance (perspective), as set by shadowlab/kit/depth_map.h.
#ifndef SHADOWLAB_LIGHT_DEPTH_GLSL
#define SHADOWLAB_LIGHT_DEPTH_GLSL

// Stored map depth d in [0,1] -> linear depth: distance from the light along its axis
// (perspective) or from the near plane (orthographic). Perspective, from GL's projection and the
// 0.5 * ndc + 0.5 of light_space.glsl: d = f (1 - n / z) / (f - n), so z = n f / (f - d (f - n)).
float lightLinearDepth(float d, vec4 lightDepth) {
    float n = lightDepth.x, f = lightDepth.y;
    return lightDepth.z > 0.5 ? n * f / (f - d * (f - n)) : d * (f - n);
}

// Map depth per texel of lateral offset on a planar receiver with normal N. The map's depth runs
// along the light's axis `lightAxis` (the view direction of the light camera; the travel direction
// for a directional light), and a texel is a step perpendicular to that axis. Across such a step
// of length l the receiver's axial depth changes by l tan(theta), theta the angle between N and
// the axis (not the ray to the light: they differ off-axis in a perspective map). A texel spans
// worldSize / res world units (orthographic) or worldSize * z / res (perspective, at axial depth
// z), and the stored depth changes by 1 / (f - n) (orthographic) or dd/dz = n f / ((f - n) z^2)
// (perspective) per world unit of axial depth. tan(theta) is capped at 10 (theta < 84 degrees):
// receivers edge-on to the light would need unbounded bias.
float receiverDepthSlope(vec3 normal, vec3 lightAxis, float d, vec4 lightDepth, vec2 worldSize) {
    float cosTheta = clamp(abs(dot(normal, lightAxis)), 0.0995, 1.0);
    float tanTheta = sqrt(1.0 - cosTheta * cosTheta) / cosTheta;
    float n = lightDepth.x, f = lightDepth.y, resolution = lightDepth.w;
    float texelWorld = max(worldSize.x, worldSize.y) / resolution;
    if (lightDepth.z > 0.5) {
        float z = lightLinearDepth(d, lightDepth);
        return tanTheta * texelWorld * z * n * f / ((f - n) * z * z);
    }
    return tanTheta * texelWorld / (f - n);
}

#endif
