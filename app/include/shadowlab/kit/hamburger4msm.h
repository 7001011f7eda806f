// Moment shadow mapping with four moments, CPU reference (Peters and Klein 2015, "Moment Shadow
// Mapping", Hamburger 4MSM, and its optimised quantisation for 16-bit storage). Pure C++/glm,
// header-only, templated on the scalar type: float, as on the GPU, where msm's shader file hamburger4msm.glsl implements the
// same formulas line for line, so tests/test_moment_shadows.cpp can check the rendered visibility
// against this file (msm.cpp also takes the quantised clear value from it); double, to check the
// mathematical properties apart from float rounding.
//
// Depths are in [0, 1] (moment_shadows.glsl); b = (z, z^2, z^3, z^4) are the "canonical" moments.
#pragma once

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>

namespace shadowlab::msm {

template <class T>
glm::vec<4, T> momentsOfDepth(T z) {
    const T z2 = z * z;
    return {z, z2, z2 * z, z2 * z2};
}

// Optimised quantisation (Peters and Klein 2015): an affine map q = Q b + o chosen so
// that, for depths in [0, 1], q fills [0, 1]^4 and the rounding of each channel to 16 bits
// disturbs the reconstruction as little as possible (plain 16-bit moments would lose the small
// differences z^4 - (z^2)^2 that carry the shape of the distribution). Because the map is affine
// it commutes with filtering: blur, bilinear and mipmaps work on q directly, and only the lookup
// undoes it. Constants as published (their matrices are written row by row for row vectors,
// q = b^T R; glm and GLSL fill matrices column by column, so the same list of numbers read into a
// mat4 gives Q with q = Q b).
inline glm::mat4 quantizationMatrix() {
    return glm::mat4(-2.07224649f, 13.7948857237f, 0.105877704f, 9.7924062118f,        //
                     32.23703778f, -59.4683975703f, -1.9077466311f, -33.7652110555f,   //
                     -68.571074599f, 82.0359750338f, 9.3496555107f, 47.9456096605f,    //
                     39.3703274134f, -35.364903257f, -6.6543490743f, -23.9728048165f);
}
inline glm::mat4 inverseQuantizationMatrix() {   // the published inverse of quantizationMatrix()
    return glm::mat4(0.2227744146f, 0.1549679261f, 0.1451988946f, 0.163127443f,      //
                     0.0771972861f, 0.1394629426f, 0.2120202157f, 0.2591432266f,     //
                     0.7926986636f, 0.7963415838f, 0.7258694464f, 0.6539092497f,     //
                     0.0319417555f, -0.1722823173f, -0.2758014811f, -0.3376131734f);
}
inline constexpr glm::vec4 kQuantizationOffset{0.035955884801f, 0.0f, 0.0f, 0.0f};

inline glm::vec4 quantizeMoments(glm::vec4 b) { return quantizationMatrix() * b + kQuantizationOffset; }
inline glm::vec4 dequantizeMoments(glm::vec4 q) { return inverseQuantizationMatrix() * (q - kQuantizationOffset); }

// Shadow intensity (0 lit, 1 shadowed) of a receiver at `depth` from filtered canonical moments.
//
// Moment bias: b' = (1 - alpha) b + alpha b*, a pull towards the moments b* of a fixed, wide
// distribution, so that the Hankel matrix below stays safely positive definite despite rounding (a
// single depth alone makes it singular) at the price of a little light leaking. The paper works
// with depths u in [-1, 1] and b*_u = (0, 0.63, 0, 0.63). Derived again for z = (u + 1) / 2 in
// [0, 1]: the moments of a mixture are the mixture of the moments and z is affine in u, so the same
// bias in z-moments uses E[z^k] = E[((u + 1) / 2)^k] of that b*_u:
//   E[z] = 1/2, E[z^2] = (0.63 + 1) / 4 = 0.4075, E[z^3] = (3 * 0.63 + 1) / 8 = 0.36125,
//   E[z^4] = (0.63 + 6 * 0.63 + 1) / 16 = 0.338125.
// (The often-copied (0.5, 0.5, 0.5, 0.5), two atoms at 0 and 1, is itself singular: with a depth
// close to either end, float rounding then turns the reconstruction into NaN.)
// Depth bias: the receiver is moved towards the light by that much.
//
// Hamburger 4MSM (the paper's algorithm, derived again here): among all depth distributions with
// moments b', take the one with three atoms, one of them at the receiver depth z_f. Its other two
// atoms z_2 < z_3 are the roots of c_1 + c_2 x + c_3 x^2 = 0 where B c = (1, z_f, z_f^2)^T and B
// is the Hankel matrix [[1, b1, b2], [b1, b2, b3], [b2, b3, b4]]. The weight of an atom z_a of a
// three-atom distribution {z_a, z_b, z_c} with moments b1, b2 follows from the first three
// moment equations (Lagrange interpolation):
//   w_a = (z_b z_c - b1 (z_b + z_c) + b2) / ((z_a - z_b) (z_a - z_c)).
// The shadow intensity is the weight in front of the receiver: 0 if z_f <= z_2; w_2 if
// z_2 < z_f <= z_3; w_2 + w_3 = 1 - w_f if z_f > z_3.
// B c = rhs is solved with B = L D L^T, L unit lower triangular:
//   D22 = b2 - b1^2, L32 = (b3 - b1 b2) / D22, D33 = b4 - b2^2 - L32^2 D22.
template <class T>
T hamburger4MsmShadowIntensity(glm::vec<4, T> moments, T depth, T depthBias, T momentBias) {
    using Vec4 = glm::vec<4, T>;
    const Vec4 biasTarget(T(0.5), T(0.4075), T(0.36125), T(0.338125));
    const Vec4 b = (T(1) - momentBias) * moments + momentBias * biasTarget;
    const T zf = depth - depthBias;

    const T d22 = b.y - b.x * b.x;
    const T l32d22 = b.z - b.x * b.y;
    const T l32 = l32d22 / d22;
    const T d33 = (b.w - b.y * b.y) - l32 * l32d22;   // D33 = b4 - b2^2 - L32^2 D22

    // Forward substitution L y = (1, z_f, z_f^2), scaling by D^-1, back substitution L^T c = y.
    T c2 = zf - b.x;
    T c3 = zf * zf - b.y - l32 * c2;
    c2 /= d22;
    c3 /= d33;
    c2 -= l32 * c3;
    const T c1 = T(1) - b.x * c2 - b.y * c3;

    // Roots of c3 x^2 + c2 x + c1.
    const T p = c2 / c3;
    const T q = c1 / c3;
    const T r = std::sqrt(std::max(T(0.25) * p * p - q, T(0)));
    const T z2 = -T(0.5) * p - r;
    const T z3 = -T(0.5) * p + r;

    T intensity;
    if (zf <= z2) {
        intensity = T(0);
    } else if (zf <= z3) {
        intensity = (zf * z3 - b.x * (zf + z3) + b.y) / ((z2 - zf) * (z2 - z3));   // w_2
    } else {
        intensity = T(1) - (z2 * z3 - b.x * (z2 + z3) + b.y) / ((zf - z2) * (zf - z3));   // 1 - w_f
    }
    return std::clamp(intensity, T(0), T(1));
}

template <class T>
T hamburger4MsmVisibility(glm::vec<4, T> moments, T depth, T depthBias, T momentBias) {
    return T(1) - hamburger4MsmShadowIntensity(moments, depth, depthBias, momentBias);
}

} // namespace shadowlab::msm
