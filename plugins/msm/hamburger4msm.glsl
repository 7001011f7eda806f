// Hamburger 4MSM and the optimised 16-bit quantisation (Peters and Klein 2015): the same formulas,
// line for line, as the CPU reference hamburger4msm.h, where they are derived. Depths in [0, 1].
#ifndef SHADOWLAB_HAMBURGER4MSM_GLSL
#define SHADOWLAB_HAMBURGER4MSM_GLSL

vec4 momentsOfDepth(float z) {
    float z2 = z * z;
    return vec4(z, z2, z2 * z, z2 * z2);
}

// q = Q b + o (matrix filled column by column with the published row-vector constants).
const mat4 kQuantizationMatrix = mat4(
    -2.07224649, 13.7948857237, 0.105877704, 9.7924062118,
    32.23703778, -59.4683975703, -1.9077466311, -33.7652110555,
    -68.571074599, 82.0359750338, 9.3496555107, 47.9456096605,
    39.3703274134, -35.364903257, -6.6543490743, -23.9728048165);
const mat4 kInverseQuantizationMatrix = mat4(
    0.2227744146, 0.1549679261, 0.1451988946, 0.163127443,
    0.0771972861, 0.1394629426, 0.2120202157, 0.2591432266,
    0.7926986636, 0.7963415838, 0.7258694464, 0.6539092497,
    0.0319417555, -0.1722823173, -0.2758014811, -0.3376131734);
const vec4 kQuantizationOffset = vec4(0.035955884801, 0.0, 0.0, 0.0);

vec4 quantizeMoments(vec4 b) { return kQuantizationMatrix * b + kQuantizationOffset; }
vec4 dequantizeMoments(vec4 q) { return kInverseQuantizationMatrix * (q - kQuantizationOffset); }

// Shadow intensity (0 lit, 1 shadowed); see hamburger4msm.h for the derivation.
float hamburger4MsmShadowIntensity(vec4 moments, float depth, float depthBias, float momentBias) {
    const vec4 biasTarget = vec4(0.5, 0.4075, 0.36125, 0.338125);
    vec4 b = (1.0 - momentBias) * moments + momentBias * biasTarget;
    float zf = depth - depthBias;

    float d22 = b.y - b.x * b.x;
    float l32d22 = b.z - b.x * b.y;
    float l32 = l32d22 / d22;
    float d33 = (b.w - b.y * b.y) - l32 * l32d22;

    float c2 = zf - b.x;
    float c3 = zf * zf - b.y - l32 * c2;
    c2 /= d22;
    c3 /= d33;
    c2 -= l32 * c3;
    float c1 = 1.0 - b.x * c2 - b.y * c3;

    float p = c2 / c3;
    float q = c1 / c3;
    float r = sqrt(max(0.25 * p * p - q, 0.0));
    float z2 = -0.5 * p - r;
    float z3 = -0.5 * p + r;

    float intensity;
    if (zf <= z2) {
        intensity = 0.0;
    } else if (zf <= z3) {
        intensity = (zf * z3 - b.x * (zf + z3) + b.y) / ((z2 - zf) * (z2 - z3));
    } else {
        intensity = 1.0 - (z2 * z3 - b.x * (z2 + z3) + b.y) / ((zf - z2) * (zf - z3));
    }
    return clamp(intensity, 0.0, 1.0);
}

#endif
