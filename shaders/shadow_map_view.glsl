// The maps a technique reported (SHADOWLAB_EXT_SHADOW_MAPS), for the host's debug views: the
// same serving rule and footprint m as app/src/groundtruth/texel_footprint.cpp (in float).
#define SHADOW_MAP_VIEW_MAX_MAPS 16
struct ReportedMap {
    mat4 worldToClip;
    vec4 sizeAndRange;   // texels x, y; view distances served [z, w)
};
layout(std140, binding = 0) uniform ReportedMaps {
    ReportedMap uMaps[SHADOW_MAP_VIEW_MAX_MAPS];
    mat4 uCameraView;
    mat4 uCameraViewProjection;
    mat4 uCameraInverseViewProjection;
    ivec4 uMapCountViewport;   // x: maps, yz: viewport pixels
};

int servingMap(vec3 world) {
    float viewDistance = -(uCameraView * vec4(world, 1.0)).z;
    for (int i = 0; i < uMapCountViewport.x; ++i) {
        if (viewDistance < uMaps[i].sizeAndRange.z || viewDistance >= uMaps[i].sizeAndRange.w) continue;
        vec4 clip = uMaps[i].worldToClip * vec4(world, 1.0);
        if (clip.w > 0.0 && all(lessThanEqual(abs(clip.xy), vec2(clip.w)))) return i;
    }
    return -1;
}

vec2 texelOf(int map, vec3 world) {
    vec4 clip = uMaps[map].worldToClip * vec4(world, 1.0);
    return (clip.xy / clip.w * 0.5 + 0.5) * uMaps[map].sizeAndRange.xy;
}
