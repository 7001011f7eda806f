// Shadow pass of the moment map with blur = compute (kit/moment_map.h): no colour target, only the
// depth buffer, into which the linear light depth that the colour pass would turn into moments is
// written (moment_depth.vert computes it). The compute blur then reads that depth back and derives
// the moments from it (separable_blur.comp), so both paths see the same depth per texel. Writing
// gl_FragDepth also makes the depth test compare linear depths: along each texel's ray they order
// the surfaces as the projected depths of the colour pass do, so the same surface is kept.
in float vLightDepth;

void main() {
    gl_FragDepth = vLightDepth;
}
