// Host main pass, fragment stage: forward Blinn-Phong. The technique's shadow term multiplies
// the direct light only; the ambient term is never shadowed. It writes the lit colour (linear,
// encoded to sRGB by the present pass), as a real renderer would. Built a second time with
// SHADOWLAB_ACCURACY_TARGETS for the frames measured for accuracy (never timed): those also write
// the shadow term with a mask of where it is comparable, and the world position and normal.
#include "common.glsl"

in VertexOut {
    vec3 worldPos;
    vec3 worldNormal;
    vec2 uv;
    flat uint objectId;
} vIn;

layout(location = 0) out vec4 outColor;
#ifdef SHADOWLAB_ACCURACY_TARGETS
layout(location = 1) out vec4 outVisibility;  // rgb shadow term, a = 1 where lit side and in cone
layout(location = 2) out vec4 outPosition;    // xyz world, w = 1 where geometry was drawn
layout(location = 3) out vec4 outNormal;      // xyz world normal (geometric side facing the viewer)
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
    // Called in uniform control flow, so techniques may use derivatives.
    vec3 shadow = shadowTerm(s);

    vec4 albedo = surfaceBaseColor(vIn.uv);
    vec3 H = normalize(L + V);
    vec3 diffuse = albedo.rgb * max(NdotL, 0.0);
    vec3 specular = NdotL > 0.0 ? uSpecular.rgb * pow(max(dot(N, H), 0.0), uSpecular.a) : vec3(0.0);
    vec3 direct = (diffuse + specular) * uLightColor.rgb * spot;
    vec3 color = uAmbient.rgb * albedo.rgb + direct * shadow;

    outColor = vec4(color, albedo.a);
#ifdef SHADOWLAB_ACCURACY_TARGETS
    bool compared = NdotL > 0.0 && spot > 0.0;
    outVisibility = vec4(shadow, compared ? 1.0 : 0.0);
    outPosition = vec4(vIn.worldPos, 1.0);
    outNormal = vec4(N, 0.0);
#endif
}
