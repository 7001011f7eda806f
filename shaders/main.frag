// Host main pass, fragment stage: forward Blinn-Phong. The technique's shadow term multiplies
// the direct light only; the ambient term is never shadowed. It writes the lit colour (linear,
// encoded to sRGB by the present pass), as a real renderer would. Built a second time with
// SHADOWLAB_ACCURACY_TARGETS for the frames measured for accuracy (never timed): those also write
// the shadow term with a mask of where it is comparable, and the world position and normal.
//
// The eye-space blur (seed 002 sec. 6.3, 9.4.2; host_shared/eye_blur_shared.h) adds two variants,
// built on first use: SHADOWLAB_EYE_BLUR_TERM writes only the shadow term of the unlit,
// unicoloured geometry (Fig. 6.5) and the view depth, for the blur; SHADOWLAB_EYE_BLUR_READ (with
// or without the accuracy targets) reads the blurred term at the pixel instead of calling
// shadowTerm() for the opaque surfaces (sec. 9.4.2: "no shadow calculations are necessary"), and
// calls it for translucent surfaces, which the term texture does not hold.
//
// Contact shadows (issue 30; host_shared/contact_shadows_shared.h): every main pass but the term
// and peel variants can take the minimum of the shadow term and the host's contact term at the
// pixel. uContactRead is 0 when contact shadows are off (the term is then exactly shadowTerm()'s)
// and for translucent surfaces, which the camera depth the contact term comes from does not hold.
//
// SHADOWLAB_TRANSLUCENT_PEEL (with the accuracy targets; evaluation frames only,
// host_shared/translucent_layers_shared.h) draws one translucent layer: fragments at or in front of
// the previous layer's depth, or at or behind the opaque depth, are discarded at the end (so
// shadowTerm() still runs in uniform control flow).
//
// Lighting (uLighting; seed 002 sec. 6.2's three rules, Fig. 6.7): phong = ambient never
// shadowed, diffuse attenuated by the shadow term (the part that hides projection aliasing, since
// N.L is small where it is large, eq. 6.2), specular attenuated too (no specular inside shadow);
// none = the term on unlit surfaces, colour = albedo (ambient + light s), no N.L and no
// specular: the projection aliasing the lighting would hide stays visible (Fig. 6.7, left).
#include "common.glsl"
#include "host_shared/eye_blur_shared.h"
#include "host_shared/contact_shadows_shared.h"
#if !defined(SHADOWLAB_EYE_BLUR_TERM) && !defined(SHADOWLAB_TRANSLUCENT_PEEL)
#define SHADOWLAB_CONTACT_READ 1
layout(binding = kContactTermUnit) uniform sampler2D uContactTerm;
layout(location = SHADOWLAB_CONTACT_READ_LOCATION) uniform int uContactRead;
#endif
#ifdef SHADOWLAB_TRANSLUCENT_PEEL
#include "host_shared/translucent_layers_shared.h"
layout(binding = kPeelPreviousDepthUnit) uniform sampler2D uPeelPreviousDepth;
layout(binding = kPeelOpaqueDepthUnit) uniform sampler2D uPeelOpaqueDepth;
#endif

in VertexOut {
    vec3 worldPos;
    vec3 worldNormal;
    vec2 uv;
    flat uint objectId;
} vIn;

#ifdef SHADOWLAB_EYE_BLUR_TERM
layout(location = 0) out vec4 outTerm;        // rgb shadow term, a = view depth
#else
layout(location = 0) out vec4 outColor;
layout(location = SHADOWLAB_LIGHTING_LOCATION) uniform int uLighting;
#endif
#ifdef SHADOWLAB_ACCURACY_TARGETS
layout(location = 1) out vec4 outVisibility;  // rgb shadow term, a = 1 where lit side and in cone
layout(location = 2) out vec4 outPosition;    // xyz world, w = 1 where geometry was drawn
layout(location = 3) out vec4 outNormal;      // xyz world normal (geometric side facing the viewer)
#endif
#ifdef SHADOWLAB_EYE_BLUR_READ
layout(binding = kEyeBlurTermUnit) uniform sampler2D uEyeBlurTerm;
layout(location = SHADOWLAB_EYE_BLUR_READ_LOCATION) uniform int uEyeBlurRead;
#endif

#include "technique_shadow.glsl"

void main() {
    vec3 N = normalize(vIn.worldNormal);
    if (!gl_FrontFacing) N = -N;
    vec3 L = directionToLight(vIn.worldPos);
    vec3 V = normalize(uCameraPosition.xyz - vIn.worldPos);
    float NdotL = dot(N, L);
    float spot = spotFactor(vIn.worldPos);

    ShadowInput s = ShadowInput(vIn.worldPos, N, L, NdotL, gl_FragCoord.xy);
#ifdef SHADOWLAB_EYE_BLUR_READ
    // uEyeBlurRead is the same for a whole draw, so shadowTerm() still runs in uniform control flow.
    vec3 shadow = uEyeBlurRead != 0 ? texelFetch(uEyeBlurTerm, ivec2(gl_FragCoord.xy), 0).rgb : shadowTerm(s);
#else
    // Called in uniform control flow, so techniques may use derivatives.
    vec3 shadow = shadowTerm(s);
#endif
#ifdef SHADOWLAB_CONTACT_READ
    if (uContactRead != 0) shadow = min(shadow, vec3(texelFetch(uContactTerm, ivec2(gl_FragCoord.xy), 0).r));
#endif

#ifdef SHADOWLAB_EYE_BLUR_TERM
    outTerm = vec4(shadow, -(uView * vec4(vIn.worldPos, 1.0)).z);
#else
    vec4 albedo = surfaceBaseColor(vIn.uv);
    vec3 color;
    if (uLighting == 0) {
        vec3 H = normalize(L + V);
        vec3 diffuse = albedo.rgb * max(NdotL, 0.0);
        vec3 specular = NdotL > 0.0 ? uSpecular.rgb * pow(max(dot(N, H), 0.0), uSpecular.a) : vec3(0.0);
        vec3 direct = (diffuse + specular) * uLightColor.rgb * spot;
        color = uAmbient.rgb * albedo.rgb + direct * shadow;
    } else {
        color = albedo.rgb * (uAmbient.rgb + uLightColor.rgb * spot * shadow);
    }
    outColor = vec4(color, albedo.a);
#endif
#ifdef SHADOWLAB_ACCURACY_TARGETS
    bool compared = NdotL > 0.0 && spot > 0.0;
    outVisibility = vec4(shadow, compared ? 1.0 : 0.0);
    outPosition = vec4(vIn.worldPos, 1.0);
    outNormal = vec4(N, 0.0);
#endif
#ifdef SHADOWLAB_TRANSLUCENT_PEEL
    // The previous layer stored this very gl_FragCoord.z in 32-bit float, so <= removes exactly
    // the surfaces already peeled; the opaque depth is 24-bit, so compare at its precision.
    const ivec2 texel = ivec2(gl_FragCoord.xy);
    const float opaque = texelFetch(uPeelOpaqueDepth, texel, 0).r;
    const float quantised = floor(gl_FragCoord.z * 16777215.0 + 0.5) / 16777215.0;
    if (gl_FragCoord.z <= texelFetch(uPeelPreviousDepth, texel, 0).r || quantised >= opaque) discard;
#endif
}
