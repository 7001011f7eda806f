// GL's cube-map addressing (GL 4.5 core, table 8.19) both ways, for passes that read a cube's
// texels face by face: a face and its coordinates st in [-1, 1]^2 (s along the texel rows, t
// along the columns, texel (x, y) of a face at st = 2 (x + 0.5, y + 0.5) / size - 1), and back.
#ifndef SHADOWLAB_CUBE_FACES_GLSL
#define SHADOWLAB_CUBE_FACES_GLSL

// Faces in GL's order: 0 +x, 1 -x, 2 +y, 3 -y, 4 +z, 5 -z.
vec3 cubeFaceDirection(int face, vec2 st) {
    float s = st.x, t = st.y;
    if (face == 0) return vec3(1.0, -t, -s);
    if (face == 1) return vec3(-1.0, -t, s);
    if (face == 2) return vec3(s, 1.0, t);
    if (face == 3) return vec3(s, -1.0, -t);
    if (face == 4) return vec3(s, -t, 1.0);
    return vec3(-s, -t, -1.0);
}

// The face a direction selects (its major axis) and its coordinates there.
int cubeFaceCoord(vec3 d, out vec2 st) {
    vec3 a = abs(d);
    if (a.x >= a.y && a.x >= a.z) {
        st = (d.x > 0.0 ? vec2(-d.z, -d.y) : vec2(d.z, -d.y)) / a.x;
        return d.x > 0.0 ? 0 : 1;
    }
    if (a.y >= a.z) {
        st = (d.y > 0.0 ? vec2(d.x, d.z) : vec2(d.x, -d.z)) / a.y;
        return d.y > 0.0 ? 2 : 3;
    }
    st = (d.z > 0.0 ? vec2(d.x, -d.y) : vec2(-d.x, -d.y)) / a.z;
    return d.z > 0.0 ? 4 : 5;
}

#endif
