// Host debug-view overlays in the camera view: the focus body B's edges and the filter kernel's
// footprint around a probed pixel (render/shadow_map_views.cpp), world-space lines and points with
// a colour each, transformed by the camera of the frame (shadow_map_view.glsl's block).
#include "shadow_map_view.glsl"
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aColour;
out vec3 vColour;

void main() {
    vColour = aColour;
    gl_Position = uCameraViewProjection * vec4(aPosition, 1.0);
}
