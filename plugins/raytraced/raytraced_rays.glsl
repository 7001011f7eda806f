// raytraced: the shadow rays of one shaded point, shared by the screen-space pass
// (raytraced_trace.comp) and the main pass's fallback for surfaces the pre-pass did not hold
// (raytraced.glsl). Needs ray_trace.glsl and the RaytracedUniforms block (raytraced_shared.h).
#ifndef RAYTRACED_RAYS_GLSL
#define RAYTRACED_RAYS_GLSL

// Visibility of the light from surface point p (unit normal n, either side): hard (N = 1) to the
// light's centre, soft the mean of N jittered stratified rays over the emitter seeded by `pixel`
// and the frame; `rays` returns the rays traced. 0 where the surface faces away from the light or
// lies outside a spot light's cone (the reference's compared pixels, groundtruth.h facesLight).
vec3 traceRays(vec3 p, vec3 n, uint pixel, out uint rays) {
    int type = int(uRtLightPosition.w + 0.5);
    vec3 lightPos = uRtLightPosition.xyz, lightDir = uRtLightDirection.xyz;
    float offset = uRtParams.x;
    vec3 toLight = type == 0 ? -lightDir : normalize(lightPos - p);
    rays = 0u;
    // Only surfaces facing the light inside a spot's cone are traced (groundtruth.h facesLight).
    if (dot(n, toLight) <= 0.0) return vec3(0.0);
    if (type == 1 && dot(-toLight, lightDir) <= uRtParams.y) return vec3(0.0);
    vec3 facing;
    vec3 origin = rtShadowOrigin(p, n, toLight, offset, facing);
    int count = int(uRtOptions.x);
    if (count <= 1 || uRtLightDirection.w <= 0.0) {
        vec3 direction;
        float tMax;
        rtEmitterRay(type, lightPos, lightDir, uRtLightDirection.w, origin, offset, vec2(0.5), true, direction, tMax);
        rays = 1u;
        return rtTransmittance(origin, direction, tMax, offset);
    }
    vec3 sum = vec3(0.0);
    for (int k = 0; k < count; ++k) {
        vec2 u = rtStratum(k, count, rtRandom2(pixel, uRtOptions.y, uint(k)));
        vec3 direction;
        float tMax;
        rtEmitterRay(type, lightPos, lightDir, uRtLightDirection.w, origin, offset, u, false, direction, tMax);
        if (dot(direction, facing) <= 0.0) continue;   // the surface itself hides this part of the emitter
        ++rays;
        sum += rtTransmittance(origin, direction, tMax, offset);
    }
    return sum / float(count);
}

#endif
