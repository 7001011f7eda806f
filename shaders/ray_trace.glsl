// Shadow rays on the GPU (issue 27): traversal of the host's BVH (app/src/render/bvh.h,
// extension SHADOWLAB_EXT_RAY_TRACING) in any stage that can read storage buffers (compute for
// the screen-space passes, fragment for translucent receivers).
//
// Bind the extension's buffers on the storage bindings below (override the RT_*_BINDING macros
// before including this file if they collide). rtTransmittance() walks the tree with a short
// stack (64 entries: the builder makes no node deeper than 60), tests triangles watertight
// (Woop, Benthin and Wald 2013, "Watertight ray/triangle intersection", JCGT 2(1)) and is an
// any-hit query: the first opaque caster ends the ray with 0; a translucent one multiplies the
// physical model (1 - a) + a t (seed 001 sec. 2.1.3; groundtruth.h crossingFactor), a, t from its
// material or, where it has a transmission texture, bilinear from the texture at the hit's uv with
// repeat wrapping (as Scene's sampleTexture and the raster passes' GL_LINEAR + GL_REPEAT). Every
// crossing multiplies once, in any order: the product needs no sorting.
//
// Counters: with RT_COUNTERS defined, rtNodeVisits and rtTriangleTests count what the calls did.
#ifndef SHADOWLAB_RAY_TRACE_GLSL
#define SHADOWLAB_RAY_TRACE_GLSL

#ifndef RT_NODE_BINDING
#define RT_NODE_BINDING 3
#endif
#ifndef RT_TRIANGLE_BINDING
#define RT_TRIANGLE_BINDING 4
#endif
#ifndef RT_UV_BINDING
#define RT_UV_BINDING 5
#endif
#ifndef RT_MATERIAL_BINDING
#define RT_MATERIAL_BINDING 6
#endif
#ifndef RT_TEXEL_BINDING
#define RT_TEXEL_BINDING 7
#endif

layout(std430, binding = RT_NODE_BINDING) readonly buffer RtNodes { vec4 rtNodes[]; };          // 2 per node
layout(std430, binding = RT_TRIANGLE_BINDING) readonly buffer RtTriangles { vec4 rtTriangles[]; }; // 3 per triangle
layout(std430, binding = RT_UV_BINDING) readonly buffer RtUvs { vec4 rtUvs[]; };                // 2 per textured triangle
layout(std430, binding = RT_MATERIAL_BINDING) readonly buffer RtMaterials { vec4 rtMaterials[]; }; // 2 per material
layout(std430, binding = RT_TEXEL_BINDING) readonly buffer RtTexels { uint rtTexels[]; };          // RGBA8

#ifdef RT_COUNTERS
uint rtNodeVisits = 0u;
uint rtTriangleTests = 0u;
#endif

const uint RT_MATERIAL_OPAQUE = 1u;
const float RT_INFINITY = uintBitsToFloat(0x7F800000u);

vec4 rtTexel(uint first, ivec2 size, ivec2 at) {
    ivec2 w = ((at % size) + size) % size;
    return unpackUnorm4x8(rtTexels[first + uint(w.y * size.x + w.x)]);
}

// sampleTexture (scene.h): bilinear between texel centres, repeat.
vec4 rtSampleTexture(uvec4 info, vec2 uv) {
    ivec2 size = ivec2(info.zw);
    vec2 st = uv * vec2(size) - 0.5;
    vec2 base = floor(st);
    vec2 f = st - base;
    ivec2 b = ivec2(base);
    return mix(mix(rtTexel(info.y, size, b), rtTexel(info.y, size, b + ivec2(1, 0)), f.x),
               mix(rtTexel(info.y, size, b + ivec2(0, 1)), rtTexel(info.y, size, b + ivec2(1, 1)), f.x), f.y);
}

// The ray, prepared once for every triangle test (Woop et al. 2013, sec. 3).
struct RtRay {
    vec3 origin;
    vec3 inverse;   // 1 / direction, with zero components nudged to +-1e-20
    float tMax;
    ivec3 k;        // kx, ky, kz: kz the dominant axis of the direction
    vec3 shear;     // Sx, Sy, Sz
};

RtRay rtMakeRay(vec3 origin, vec3 direction, float tMax) {
    RtRay r;
    r.origin = origin;
    vec3 d = direction;
    for (int i = 0; i < 3; ++i)
        if (abs(d[i]) < 1e-20) d[i] = d[i] < 0.0 ? -1e-20 : 1e-20;
    r.inverse = 1.0 / d;
    r.tMax = tMax;
    vec3 a = abs(direction);
    int kz = a.x > a.y ? (a.x > a.z ? 0 : 2) : (a.y > a.z ? 1 : 2);
    int kx = (kz + 1) % 3, ky = (kx + 1) % 3;
    if (direction[kz] < 0.0) { int t = kx; kx = ky; ky = t; }
    r.k = ivec3(kx, ky, kz);
    r.shear = vec3(direction[kx] / direction[kz], direction[ky] / direction[kz], 1.0 / direction[kz]);
    return r;
}

// Slab test; the far distance widened by 2 gamma(3) (Ize 2013) so rounding never loses a box
// whose triangle the watertight test would hit.
bool rtHitsBox(RtRay r, uint node) {
    vec3 t0 = (rtNodes[2u * node].xyz - r.origin) * r.inverse;
    vec3 t1 = (rtNodes[2u * node + 1u].xyz - r.origin) * r.inverse;
    vec3 n = min(t0, t1), f = max(t0, t1);
    float enter = max(max(n.x, n.y), max(n.z, 0.0));
    float leave = min(min(f.x, f.y), min(f.z, r.tMax)) * 1.0000004;
    return enter <= leave;
}

// Watertight test of triangle `tri`: true with the unnormalised barycentrics (u, v, w: weights of
// v0, v1, v2; divide by their sum) when the ray hits it at t in (0, tMax).
bool rtHitTriangle(RtRay r, uint tri, out vec3 uvw, out float t) {
    vec3 a = rtTriangles[3u * tri].xyz - r.origin;
    vec3 b = rtTriangles[3u * tri + 1u].xyz - r.origin;
    vec3 c = rtTriangles[3u * tri + 2u].xyz - r.origin;
    float ax = a[r.k.x] - r.shear.x * a[r.k.z], ay = a[r.k.y] - r.shear.y * a[r.k.z];
    float bx = b[r.k.x] - r.shear.x * b[r.k.z], by = b[r.k.y] - r.shear.y * b[r.k.z];
    float cx = c[r.k.x] - r.shear.x * c[r.k.z], cy = c[r.k.y] - r.shear.y * c[r.k.z];
    float u = cx * by - cy * bx, v = ax * cy - ay * cx, w = bx * ay - by * ax;
#ifndef RT_NO_DOUBLE
    // An edge through the ray exactly: decide it in double precision, as the paper does.
    if (u == 0.0 || v == 0.0 || w == 0.0) {
        u = float(double(cx) * double(by) - double(cy) * double(bx));
        v = float(double(ax) * double(cy) - double(ay) * double(cx));
        w = float(double(bx) * double(ay) - double(by) * double(ax));
    }
#endif
    if ((u < 0.0 || v < 0.0 || w < 0.0) && (u > 0.0 || v > 0.0 || w > 0.0)) return false;
    float det = u + v + w;
    if (det == 0.0) return false;
    t = (u * r.shear.z * a[r.k.z] + v * r.shear.z * b[r.k.z] + w * r.shear.z * c[r.k.z]) / det;
    uvw = vec3(u, v, w) / det;
    return t > 0.0 && t < r.tMax;
}

// The translucency model of the crossings (TranslucencyModel, technique.h): 0 opaque (every
// caster blocks), 1 coverage 1 - a, 2 physical (1 - a) + a t (the default), 3 modified (1 - a) t,
// 4 ignore (translucent casters let everything through). Set it before tracing.
uint rtTranslucencyModel = 2u;

// What a hit on triangle `tri` lets through: 0 for an opaque material, else the model's factor
// (physical: (1 - a) + a t).
vec3 rtCrossing(uint tri, vec3 uvw) {
    uint material = floatBitsToUint(rtTriangles[3u * tri].w);
    vec4 ta = rtMaterials[2u * material];
    uvec4 info = floatBitsToUint(rtMaterials[2u * material + 1u]);
    if ((info.x & RT_MATERIAL_OPAQUE) != 0u || rtTranslucencyModel == 0u) return vec3(0.0);
    if (rtTranslucencyModel == 4u) return vec3(1.0);
    if (info.z > 0u) {
        uint record = floatBitsToUint(rtTriangles[3u * tri + 1u].w);
        vec4 uv01 = rtUvs[2u * record];
        vec2 uv2 = rtUvs[2u * record + 1u].xy;
        ta = rtSampleTexture(info, uvw.x * uv01.xy + uvw.y * uv01.zw + uvw.z * uv2);
    }
    float alpha = clamp(ta.a, 0.0, 1.0);
    vec3 t = clamp(ta.rgb, 0.0, 1.0);
    if (rtTranslucencyModel == 1u) return vec3(1.0 - alpha);
    if (rtTranslucencyModel == 3u) return (1.0 - alpha) * t;
    return (1.0 - alpha) + alpha * t;
}

// Light reaching origin + tMax * direction (direction need not be unit; tMax in its units;
// RT_INFINITY for a directional light): rgb transmittance, 0 when an opaque caster blocks.
// Translucent crossings of one object less than `merge` apart along the ray count once: a ray
// through the shared edge of two of its triangles hits both, and the reference, which restarts
// its search `merge` (its ray offset) past each hit, counts that surface once.
vec3 rtTransmittance(vec3 origin, vec3 direction, float tMax, float merge) {
    RtRay r = rtMakeRay(origin, direction, tMax);
    vec3 throughput = vec3(1.0);
    float crossedT[4];
    uint crossedObject[4];
    int crossed = 0;
    if (!rtHitsBox(r, 0u)) return throughput;
    uint stack[64];
    int top = 0;
    uint current = 0u;
    for (;;) {
        uint first = floatBitsToUint(rtNodes[2u * current].w);
        uint count = floatBitsToUint(rtNodes[2u * current + 1u].w);
        if (count > 0u) {
            for (uint i = first; i < first + count; ++i) {
#ifdef RT_COUNTERS
                ++rtTriangleTests;
#endif
                vec3 uvw;
                float t;
                if (!rtHitTriangle(r, i, uvw, t)) continue;
                vec3 factor = rtCrossing(i, uvw);
                if (all(equal(factor, vec3(0.0)))) return factor;
                uint object = floatBitsToUint(rtTriangles[3u * i + 2u].w);
                bool again = false;
                for (int j = 0; j < min(crossed, 4); ++j)
                    again = again || (crossedObject[j] == object && abs(crossedT[j] - t) < merge);
                if (again) continue;
                crossedT[crossed % 4] = t;
                crossedObject[crossed % 4] = object;
                ++crossed;
                throughput *= factor;
                if (all(equal(throughput, vec3(0.0)))) return throughput;
            }
        } else {
#ifdef RT_COUNTERS
            ++rtNodeVisits;
#endif
            bool left = rtHitsBox(r, first), right = rtHitsBox(r, first + 1u);
            if (left && right) {
                stack[top++] = first + 1u;
                current = first;
                continue;
            }
            if (left || right) {
                current = left ? first : first + 1u;
                continue;
            }
        }
        if (top == 0) break;
        current = stack[--top];
    }
    return throughput;
}

// ---------------------------------------------------------------------------------------------
// Shadow rays as the Embree reference casts them (app/src/groundtruth/embree/embree_groundtruth.cpp).

// Where a point's shadow rays start: p + n * offset, n turned towards the light (`toLight`).
vec3 rtShadowOrigin(vec3 p, vec3 n, vec3 toLight, float offset, out vec3 facing) {
    facing = dot(n, toLight) < 0.0 ? -n : n;
    return p + facing * offset;
}

// Duff et al. 2017 orthonormal basis (the reference's orthonormalBasis).
void rtBasis(vec3 n, out vec3 t, out vec3 b) {
    float s = n.z >= 0.0 ? 1.0 : -1.0;
    float a = -1.0 / (s + n.z);
    float c = n.x * n.y * a;
    t = vec3(1.0 + s * n.x * n.x * a, s * c, -s * n.x);
    b = vec3(c, s + n.y * n.y * a, -n.y);
}

// Shirley and Chiu's concentric map, [0,1)^2 -> unit disc.
vec2 rtConcentricDisc(vec2 u) {
    vec2 o = 2.0 * u - 1.0;
    if (o.x == 0.0 && o.y == 0.0) return vec2(0.0);
    const float quarterPi = 0.78539816;
    float r, phi;
    if (abs(o.x) > abs(o.y)) {
        r = o.x;
        phi = quarterPi * (o.y / o.x);
    } else {
        r = o.y;
        phi = 2.0 * quarterPi - quarterPi * (o.x / o.y);
    }
    return r * vec2(cos(phi), sin(phi));
}

// A shadow ray to the emitter (the reference's EmitterSampler): light type 0 directional, 1 spot,
// 2 point; lightDir the travel direction, size the radius (angular for directional lights).
// `u` in [0,1)^2 picks the point (uniform in area on the disc, in solid angle on the cone);
// center = true aims at the centre. tMax is the distance less `offset` (infinite for directional).
void rtEmitterRay(int type, vec3 lightPos, vec3 lightDir, float size, vec3 origin, float offset, vec2 u, bool center,
                  out vec3 direction, out float tMax) {
    if (type == 0) {
        direction = -lightDir;
        tMax = RT_INFINITY;
        if (center) return;
        vec3 t, b;
        rtBasis(direction, t, b);
        vec2 d = rtConcentricDisc(u);
        float s = sin(0.5 * size);
        float r2 = dot(d, d);
        float cosTheta = 1.0 - r2 * 2.0 * s * s;
        float sinTheta = sqrt(max(0.0, 1.0 - cosTheta * cosTheta));
        float r = sqrt(r2);
        vec2 phi = r > 0.0 ? d / r : vec2(1.0, 0.0);
        direction = normalize(cosTheta * direction + sinTheta * (phi.x * t + phi.y * b));
        return;
    }
    vec3 target = lightPos;
    if (!center) {
        vec3 toPoint = origin - lightPos;
        float l = length(toPoint);
        vec3 axis = type == 1 || l == 0.0 ? lightDir : toPoint / l;
        vec3 t, b;
        rtBasis(axis, t, b);
        vec2 d = rtConcentricDisc(u);
        target = lightPos + size * (d.x * t + d.y * b);
    }
    vec3 toTarget = target - origin;
    float distance = length(toTarget);
    if (distance == 0.0) {
        direction = -lightDir;
        tMax = 0.0;
        return;
    }
    direction = toTarget / distance;
    tMax = max(0.0, distance - offset);
}

// Counter-based random numbers (a 32-bit hash, Jarzynski and Olano 2020's pcg3d reduced to one
// lane): element k of pixel p at seed s, independent of what was drawn before.
uint rtHash(uint v) {
    uint state = v * 747796405u + 2891336453u;
    uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}
vec2 rtRandom2(uint pixel, uint seed, uint k) {
    uint h = rtHash(pixel ^ rtHash(seed + rtHash(k)));
    uint g = rtHash(h ^ 0x9E3779B9u);
    return vec2(h >> 8, g >> 8) * (1.0 / 16777216.0);
}

// Sample k of N over the unit square, jittered stratified as the reference's Strata: an nx x ny
// grid (nx = floor(sqrt N)), the N - nx ny left over uniform.
vec2 rtStratum(int k, int n, vec2 jitter) {
    int nx = max(1, int(sqrt(float(n)) + 1e-4));
    int ny = n / nx;
    if (k >= nx * ny) return jitter;
    return vec2((float(k % nx) + jitter.x) / float(nx), (float(k / nx) + jitter.y) / float(ny));
}

#endif
