// Filterable shadow maps (vsm, esm, evsm, msm): the CPU reference of Hamburger 4MSM and its 16-bit
// quantisation (plugins/msm/hamburger4msm.h) against the properties the paper states, the rendered
// MSM visibility against that reference applied to the plugin's own moment texture, and rendered
// visibility on the built-in scenes: the analytic shadow of the cube, penumbrae that widen with the
// blur, VSM's light bleeding on `overlap` (and its reduction), the compute blur against the fragment
// blur texel for texel, memory accounting, accuracy bounds.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <set>

#include "shadowlab/kit/hamburger4msm.h"
#include "shadowlab/kit/moment_light_space.h"
#include "shadowlab/kit/moment_map_shared.h"
#include "render/light_space.h"
#include "test_support.h"

using namespace shadowlab;
namespace shadowlab::kit {
using shared::moment_map::BlurUniforms;
using shared::moment_map::MomentMapUniforms;
}
using Mode = ReferenceOptions::Mode;

namespace {

const char* const kMomentTechniques[] = {"vsm", "esm", "evsm", "msm"};

// Small maps keep llvmpipe fast; 1024 texels over the cube scene's 20 m ground is about 3.5 cm.
const std::vector<std::string> kFastMap = {"resolution=1024"};

std::vector<std::string> withFastMap(std::vector<std::string> sets) {
    sets.insert(sets.begin(), kFastMap.begin(), kFastMap.end());
    return sets;
}

bool finiteUnit(const glm::vec4& v) { return std::isfinite(v.r) && v.r >= 0.0f && v.r <= 1.0f; }

// ---------------------------------------------------------------------------------------------
// Hamburger 4MSM on the CPU

// Moments of a distribution of depths with weights (normalised here).
glm::vec4 mixtureMoments(const std::vector<float>& depths, const std::vector<float>& weights) {
    glm::vec4 b(0.0f);
    float total = 0.0f;
    for (size_t i = 0; i < depths.size(); ++i) {
        b += weights[i] * msm::momentsOfDepth(depths[i]);
        total += weights[i];
    }
    return b / total;
}

constexpr float kMomentBias = 3e-5f;

TEST(Hamburger4Msm, ASingleDepthIsReconstructedExactlyUpToTheBias) {
    for (float z0 : {0.05f, 0.3f, 0.5f, 0.77f, 0.95f}) {
        SCOPED_TRACE(z0);
        const glm::vec4 b = msm::momentsOfDepth(z0);
        // In front of (and at) the only occluder: lit, but for the bias's own mass in front (alpha / 2
        // at depth 0).
        for (float z : {0.0f, z0 - 0.2f, z0 - 0.01f, z0 - 0.001f, z0}) {
            if (z < 0.0f) continue;
            EXPECT_NEAR(msm::hamburger4MsmVisibility(b, z, 0.0f, kMomentBias), 1.0f, 1e-4f) << "receiver at " << z;
        }
        // Behind it by more than the bias smears: shadowed.
        for (float z : {z0 + 0.03f, z0 + 0.1f, 1.0f}) {
            if (z > 1.0f) continue;
            EXPECT_LT(msm::hamburger4MsmVisibility(b, z, 0.0f, kMomentBias), 0.01f) << "receiver at " << z;
        }
        // The depth bias moves the step: a receiver 0.002 behind is lit with a bias of 0.003.
        EXPECT_NEAR(msm::hamburger4MsmVisibility(b, z0 + 0.002f, 0.003f, kMomentBias), 1.0f, 1e-4f);
    }
}

TEST(Hamburger4Msm, TwoEqualDepthsGiveHalfShadowBetweenThem) {
    const glm::vec4 b = mixtureMoments({0.3f, 0.6f}, {1.0f, 1.0f});
    EXPECT_NEAR(msm::hamburger4MsmVisibility(b, 0.45f, 0.0f, kMomentBias), 0.5f, 0.01f);
    EXPECT_NEAR(msm::hamburger4MsmVisibility(b, 0.2f, 0.0f, kMomentBias), 1.0f, 1e-4f);
    EXPECT_LT(msm::hamburger4MsmVisibility(b, 0.75f, 0.0f, kMomentBias), 0.01f);
}

TEST(Hamburger4Msm, BoundedAndMonotoneInTheReceiverDepthOnRandomDistributions) {
    // Monotone (a farther receiver is never more lit) is a property of the formula: checked in
    // double. In float, as on the GPU, rounding makes small bumps where the Hankel matrix is nearly
    // singular: bounded here, and never NaN (it was, with the bias towards (0.5, 0.5, 0.5, 0.5)).
    std::mt19937 random(2015);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    for (int trial = 0; trial < 1000; ++trial) {
        const int atoms = 1 + trial % 5;
        glm::dvec4 b(0.0);
        double total = 0.0;
        for (int i = 0; i < atoms; ++i) {
            const double weight = 0.05 + unit(random);
            b += weight * msm::momentsOfDepth(unit(random));
            total += weight;
        }
        b /= total;
        const glm::vec4 bFloat(b);
        double previous = 1.0, previousFloat = 1.0;
        for (int step = 0; step <= 400; ++step) {
            const double z = double(step) / 400.0;
            const double v = msm::hamburger4MsmVisibility(b, z, 0.0, double(kMomentBias));
            const float vFloat = msm::hamburger4MsmVisibility(bFloat, float(z), 0.0f, kMomentBias);
            ASSERT_TRUE(std::isfinite(v) && std::isfinite(vFloat)) << "trial " << trial << " z " << z;
            ASSERT_GE(v, 0.0);
            ASSERT_LE(v, 1.0);
            ASSERT_GE(vFloat, 0.0f);
            ASSERT_LE(vFloat, 1.0f);
            ASSERT_LE(v, previous + 1e-9) << "trial " << trial << " z " << z;
            ASSERT_LE(vFloat, previousFloat + 0.02) << "trial " << trial << " z " << z;
            previous = v;
            previousFloat = vFloat;
        }
    }
}

TEST(Hamburger4Msm, PublishedQuantizationMatricesAreInverses) {
    const glm::mat4 product = msm::quantizationMatrix() * msm::inverseQuantizationMatrix();
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) EXPECT_NEAR(product[c][r], c == r ? 1.0f : 0.0f, 2e-5f) << c << "," << r;
}

TEST(Hamburger4Msm, QuantizedMomentsFillTheUnitCubeAndRoundTripWithin16BitPrecision) {
    // Rounding each channel to 16 bits moves it by at most half a step; the inverse spreads that
    // over b by at most the row sums of |Q^-1|.
    const glm::mat4 inverse = msm::inverseQuantizationMatrix();
    glm::vec4 bound(0.0f);
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) bound[r] += std::abs(inverse[c][r]) * 0.5f / 65535.0f;
    for (int step = 0; step <= 1000; ++step) {
        const float z = float(step) / 1000.0f;
        const glm::vec4 b = msm::momentsOfDepth(z);
        const glm::vec4 q = msm::quantizeMoments(b);
        for (int i = 0; i < 4; ++i) {
            EXPECT_GE(q[i], -1e-6f) << "z " << z;
            EXPECT_LE(q[i], 1.0f + 1e-6f) << "z " << z;
        }
        const glm::vec4 exact = msm::dequantizeMoments(q);
        glm::vec4 stored;
        for (int i = 0; i < 4; ++i) stored[i] = std::round(std::clamp(q[i], 0.0f, 1.0f) * 65535.0f) / 65535.0f;
        const glm::vec4 rounded = msm::dequantizeMoments(stored);
        for (int i = 0; i < 4; ++i) {
            // Float arithmetic with coefficients up to 82: a few 1e-6 without any rounding to 16 bits.
            EXPECT_NEAR(exact[i], b[i], 1e-5f) << "z " << z << " moment " << i;
            EXPECT_NEAR(rounded[i], b[i], bound[i] + 1e-5f) << "z " << z << " moment " << i;
        }
        // And the reconstruction survives the rounding: the step stays at the stored depth.
        if (z > 0.05f && z < 0.95f) {
            EXPECT_NEAR(msm::hamburger4MsmVisibility(rounded, z - 0.01f, 0.0f, kMomentBias), 1.0f, 1e-4f);
            EXPECT_LT(msm::hamburger4MsmVisibility(rounded, z + 0.05f, 0.0f, kMomentBias), 0.02f);
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Rendered scenes

class MomentShadows : public ::testing::Test {
protected:
    void load(const std::string& scene) {
        app_.reset();   // one GL context at a time
        app_ = test::makeHeadlessApp(scene, {320, 240});
        ASSERT_TRUE(app_);
    }
    std::vector<glm::vec4> render(const std::string& technique, const std::vector<std::string>& sets = {}) {
        return test::renderVisibility(*app_, technique, withFastMap(sets));
    }
    std::unique_ptr<App> app_;
};

struct CubeStats {
    int deepInside = 0, farOutside = 0;
    double worstInside = 0.0, worstOutside = 1.0;   // largest visibility inside, smallest outside
    double meanInside = 0.0;
    int penumbra = 0;                               // ground pixels with 0.05 < v < 0.95
};

CubeStats cubeStats(const std::vector<glm::vec4>& visibility, const test::GroundClassification& ground, int band) {
    CubeStats s;
    for (int y = 0; y < ground.size.y; ++y)
        for (int x = 0; x < ground.size.x; ++x) {
            const size_t i = size_t(y) * size_t(ground.size.x) + size_t(x);
            if (ground.analytic[i] < 0) continue;
            const double v = visibility[i].r;
            if (v > 0.05 && v < 0.95) ++s.penumbra;
            if (ground.nearBoundary(x, y, band)) continue;
            if (ground.analytic[i] == 1) {
                ++s.deepInside;
                s.worstInside = std::max(s.worstInside, v);
                s.meanInside += v;
            } else {
                ++s.farOutside;
                s.worstOutside = std::min(s.worstOutside, v);
            }
        }
    if (s.deepInside > 0) s.meanInside /= s.deepInside;
    return s;
}

TEST_F(MomentShadows, EveryTechniqueRendersTheBuiltInScenesWithValidVisibility) {
    for (const char* scene : {"cube", "contact", "overlap"}) {
        load(scene);
        for (const char* technique : kMomentTechniques) {
            SCOPED_TRACE(std::string(technique) + " on " + scene);
            const auto visibility = render(technique, {"kernel=5", "mipmaps=true"});
            int compared = 0, invalid = 0, dark = 0, lit = 0;
            for (const auto& v : visibility) {
                if (v.a < 0.5f) continue;
                ++compared;
                invalid += !finiteUnit(v);
                dark += v.r < 0.1f;
                lit += v.r > 0.9f;
            }
            EXPECT_GT(compared, 10000);
            EXPECT_EQ(invalid, 0) << "NaN or out-of-range visibility";
            EXPECT_GT(dark, 300) << "a shadow is in view";
            EXPECT_GT(lit, compared / 2) << "most of the scene is lit";
        }
    }
}

TEST_F(MomentShadows, DarkDeepInsideTheCubesAnalyticShadowAndLitFarOutside) {
    load("cube");
    // Away from the boundary by more than the blur (5 taps of 3.5 cm) and bilinear footprint seen at
    // 320x240: 6 pixels.
    struct Case {
        const char* technique;
        std::vector<std::string> sets;
    };
    const Case cases[] = {{"vsm", {"kernel=5"}},
                          {"vsm", {"kernel=5", "derivative_moment=true", "mipmaps=true"}},
                          {"esm", {"kernel=5"}},
                          {"evsm", {"kernel=5"}},
                          {"msm", {"kernel=5"}},
                          {"msm", {"kernel=5", "storage=rgba16"}}};
    for (const Case& c : cases) {
        SCOPED_TRACE(c.technique + std::string(" ") + (c.sets.size() > 1 ? c.sets[1] : ""));
        const auto visibility = render(c.technique, c.sets);
        const test::GroundClassification ground = test::classifyGround(*app_);
        const CubeStats s = cubeStats(visibility, ground, 6);
        std::printf("%s: inside %d worst %.3f mean %.4f, outside %d worst %.3f, penumbra %d\n", c.technique,
                    s.deepInside, s.worstInside, s.meanInside, s.farOutside, s.worstOutside, s.penumbra);
        EXPECT_GT(s.deepInside, 200);
        EXPECT_GT(s.farOutside, 5000);
        EXPECT_LT(s.worstInside, 0.15) << "deep inside the shadow";
        EXPECT_GT(s.worstOutside, 0.9) << "far outside the shadow";
    }
}

TEST_F(MomentShadows, BlurWidensThePenumbra) {
    load("cube");
    for (const char* technique : kMomentTechniques) {
        SCOPED_TRACE(technique);
        const test::GroundClassification ground = [&] {
            render(technique, {"kernel=1"});
            return test::classifyGround(*app_);
        }();
        const int sharp = cubeStats(render(technique, {"kernel=1"}), ground, 6).penumbra;
        const int box = cubeStats(render(technique, {"kernel=9", "filter=box"}), ground, 6).penumbra;
        const int wide = cubeStats(render(technique, {"kernel=21", "filter=box"}), ground, 6).penumbra;
        const int gaussian = cubeStats(render(technique, {"kernel=21", "filter=gaussian"}), ground, 6).penumbra;
        std::printf("%s penumbra: 1 -> %d, box 9 -> %d, box 21 -> %d, gaussian 21 -> %d\n", technique, sharp, box,
                    wide, gaussian);
        EXPECT_GT(box, sharp * 3 / 2);
        EXPECT_GT(wide, box * 3 / 2);
        EXPECT_LT(gaussian, wide) << "sigma = N / 6: narrower than the box of the same taps";
        EXPECT_GT(gaussian, sharp);
    }
}

// `overlap`: a small plate high up over a large plate low down. Ground under the low plate is in
// its shadow; along the edge of the high plate's shadow, a filter window sees both plates' depths,
// the variance is large and VSM's Chebyshev bound lets light through (seed 000 Fig. 4.12c).
struct OverlapRegions {
    std::vector<uint8_t> bleedRing;   // ground, deep in the low plate's shadow, near the high plate's edge
    int count = 0;
};

Bounds worldBoxOf(App& app, const std::string& name) {
    for (const auto& object : app.scene().objects)
        if (object.name == name) {
            Bounds b{glm::vec3(1e30f), glm::vec3(-1e30f)};
            for (const Vertex& v : app.scene().meshes[object.mesh].vertices) {
                const glm::vec3 w = glm::vec3(object.transform * glm::vec4(v.position, 1.0f));
                b.min = glm::min(b.min, w);
                b.max = glm::max(b.max, w);
            }
            return b;
        }
    ADD_FAILURE() << "no object named " << name;
    return {};
}

bool rayHitsGrownBox(glm::vec3 origin, glm::vec3 direction, Bounds box, float grow) {
    const glm::vec3 g(grow, 0.0f, grow);   // plates: grow in x and z only
    return test::rayHitsBox(origin, direction, glm::mat4(1.0f), box.min - g, box.max + g);
}

OverlapRegions overlapRegions(App& app, float ringHalfWidth) {
    const Bounds low = worldBoxOf(app, "low plate"), high = worldBoxOf(app, "high plate");
    const glm::vec3 toLight = -glm::normalize(app.light().direction);
    const auto positions = test::readTarget(app, MainTarget::Position);
    const auto normals = test::readTarget(app, MainTarget::Normal);
    OverlapRegions out{std::vector<uint8_t>(positions.size(), 0)};
    for (size_t i = 0; i < positions.size(); ++i) {
        const glm::vec3 p(positions[i]);
        if (positions[i].w < 0.5f || std::abs(p.y) > 1e-3f || normals[i].y < 0.99f) continue;
        const bool deepUnderLow = rayHitsGrownBox(p, toLight, low, -0.3f);
        const bool nearHighEdge = rayHitsGrownBox(p, toLight, high, ringHalfWidth) &&
                                  !rayHitsGrownBox(p, toLight, high, -ringHalfWidth);
        if (deepUnderLow && nearHighEdge) {
            out.bleedRing[i] = 1;
            ++out.count;
        }
    }
    return out;
}

double meanOver(const std::vector<glm::vec4>& visibility, const std::vector<uint8_t>& mask) {
    double sum = 0.0;
    int n = 0;
    for (size_t i = 0; i < mask.size(); ++i)
        if (mask[i]) {
            sum += visibility[i].r;
            ++n;
        }
    return n ? sum / n : 0.0;
}

TEST_F(MomentShadows, VsmBleedsLightOnOverlapAndTheReductionRemovesIt) {
    load("overlap");
    const auto hard = test::renderVisibility(*app_, "shadowmap", {"resolution=1024"});
    const OverlapRegions regions = overlapRegions(*app_, 0.15f);
    ASSERT_GT(regions.count, 200) << "the ring around the high plate's shadow is in view";
    const double hardMean = meanOver(hard, regions.bleedRing);
    const double bleeding = meanOver(render("vsm", {"kernel=9", "light_bleeding=0"}), regions.bleedRing);
    const double reduced = meanOver(render("vsm", {"kernel=9", "light_bleeding=0.4"}), regions.bleedRing);
    const double evsm = meanOver(render("evsm", {"kernel=9"}), regions.bleedRing);
    const double msmBleeding = meanOver(render("msm", {"kernel=9"}), regions.bleedRing);
    std::printf("overlap ring (%d px): shadowmap %.4f vsm %.4f vsm reduced %.4f evsm %.4f msm %.4f\n", regions.count,
                hardMean, bleeding, reduced, evsm, msmBleeding);
    EXPECT_LT(hardMean, 0.01) << "the hard shadow map has the ring in full shadow";
    EXPECT_GT(bleeding, hardMean + 0.1) << "VSM's known light bleeding (seed 000 Fig. 4.12c)";
    EXPECT_LT(reduced, 0.03) << "bleeding reduction 0.4 removes it";
    EXPECT_LT(msmBleeding, bleeding) << "four moments bleed less than two";
    EXPECT_LT(evsm, bleeding) << "the exponential warp bleeds less than plain VSM";
}

// ---------------------------------------------------------------------------------------------
// MSM on the GPU against the CPU reference, on the plugin's own moment texture

struct MomentTexture {
    int width = 0, height = 0;
    std::vector<glm::vec4> texels;
    glm::vec4 fetch(int x, int y) const {
        x = std::clamp(x, 0, width - 1);
        y = std::clamp(y, 0, height - 1);
        return texels[size_t(y) * size_t(width) + size_t(x)];
    }
    // GL_LINEAR with GL_CLAMP_TO_EDGE at level 0.
    glm::vec4 bilinear(glm::vec2 uv) const {
        const glm::vec2 t = uv * glm::vec2(width, height) - 0.5f;
        const glm::ivec2 i = glm::ivec2(glm::floor(t));
        const glm::vec2 f = t - glm::floor(t);
        return glm::mix(glm::mix(fetch(i.x, i.y), fetch(i.x + 1, i.y), f.x),
                        glm::mix(fetch(i.x, i.y + 1), fetch(i.x + 1, i.y + 1), f.x), f.y);
    }
};

MomentTexture readMoments(App& app, const std::string& technique) {
    std::string error;
    LoadedTechnique* loaded = app.techniques().get(technique, error);
    EXPECT_TRUE(loaded) << error;
    MomentTexture out;
    if (!loaded) return out;
    for (const DebugImage& image : loaded->host().debugImages()) {
        if (image.name != "moments") continue;
        EXPECT_EQ(image.kind, DebugImageKind::Moments);
        glGetTextureLevelParameteriv(image.texture, 0, GL_TEXTURE_WIDTH, &out.width);
        glGetTextureLevelParameteriv(image.texture, 0, GL_TEXTURE_HEIGHT, &out.height);
        out.texels.resize(size_t(out.width) * size_t(out.height));
        glGetTextureImage(image.texture, 0, GL_RGBA, GL_FLOAT, GLsizei(out.texels.size() * sizeof(glm::vec4)),
                          out.texels.data());
    }
    EXPECT_FALSE(out.texels.empty()) << technique << " registers a debug image named 'moments'";
    return out;
}

TEST_F(MomentShadows, MsmRenderedVisibilityMatchesTheCpuReconstructionOfItsMomentTexture) {
    for (const char* scene : {"cube", "overlap"}) {
        load(scene);
        for (const bool quantized : {false, true}) {
            SCOPED_TRACE(std::string(scene) + (quantized ? " 16-bit" : " 32-bit"));
            const float momentBias = 3e-5f, depthBias = 0.001f;
            const auto visibility = render("msm", {"kernel=7", "filter=gaussian", quantized ? "storage=rgba16" : "storage=rgba32f",
                                                   "moment_bias=3e-5", "depth_bias=0.001", "light_bleeding=0"});
            const MomentTexture moments = readMoments(*app_, "msm");
            ASSERT_EQ(moments.width, 1024);
            // The plugin's light space, rebuilt from the host's fit and the same rule for the depth.
            const kit::MomentLightSpace space = kit::fitMomentLightSpace(
                fitLightSpace(app_->light(), app_->renderer().bounds(DrawSet::All)),
                app_->renderer().bounds(DrawSet::Casters), app_->renderer().bounds(DrawSet::All));
            const auto positions = test::readTarget(*app_, MainTarget::Position);
            int compared = 0, penumbra = 0, close = 0;
            double worst = 0.0;
            for (size_t i = 0; i < positions.size(); i += 7) {   // a spread-out subset of pixels
                if (positions[i].w < 0.5f || visibility[i].a < 0.5f) continue;
                const glm::vec3 world(positions[i]);
                const glm::vec4 clip = space.light.viewProjection * glm::vec4(world, 1.0f);
                const glm::vec2 uv = glm::vec2(clip) / clip.w * 0.5f + 0.5f;
                if (uv.x < 0.0f || uv.y < 0.0f || uv.x > 1.0f || uv.y > 1.0f) continue;
                glm::vec4 b = moments.bilinear(uv);
                if (quantized) b = msm::dequantizeMoments(b);
                const float depth = kit::linearLightDepth(space, world);
                const float expected = msm::hamburger4MsmVisibility(b, depth, depthBias, momentBias);
                const double error = std::abs(double(visibility[i].r) - double(expected));
                ++compared;
                penumbra += expected > 0.05f && expected < 0.95f;
                close += error < 0.01;
                worst = std::max(worst, error);
            }
            std::printf("msm gpu vs cpu on %s (%s): %d compared, %d penumbra, %d within 0.01, worst %.4f\n", scene,
                        quantized ? "16" : "32", compared, penumbra, close, worst);
            EXPECT_GT(compared, 1000);
            EXPECT_GT(penumbra, 20) << "the comparison covers penumbra pixels, not only flat 0 and 1";
            EXPECT_GE(close, compared * 99 / 100) << "within 0.01 of the CPU reference";
            EXPECT_LT(worst, 0.05);
        }
    }
}

// ---------------------------------------------------------------------------------------------
// The moment map's two paths (kit/moment_map.h): blur = compute (the light renders depth only; a
// compute pass derives the moments and blurs along x in shared memory, a second along y) against
// blur = fragment (a moment colour target and two full-screen blur passes), on the same texels.

// Largest difference over every texel and channel, relative to max(1, |value|): evsm's moments
// reach exp(2 c+) = e^80, where float rounding alone is far above 1e-5 in absolute terms.
double largestDifference(const MomentTexture& a, const MomentTexture& b) {
    EXPECT_EQ(a.texels.size(), b.texels.size());
    double worst = 0.0;
    for (size_t i = 0; i < std::min(a.texels.size(), b.texels.size()); ++i)
        for (int c = 0; c < 4; ++c) {
            const double x = a.texels[i][c], y = b.texels[i][c];
            const double difference = std::abs(x - y) / std::max(1.0, std::abs(x));
            worst = std::max(worst, std::isfinite(difference) ? difference : 1e30);
        }
    return worst;
}

TEST_F(MomentShadows, ComputeBlurMatchesTheFragmentBlurTexelForTexel) {
    struct Case {
        const char* technique;
        std::vector<std::string> sets;
        double tolerance;
    };
    // One 16-bit level is 1.5e-5: with rgba16 storage the scratch and the map round to it, and a
    // difference of float rounding before a rounding can move a texel by one level.
    const double rgba16Level = 1.0 / 65535.0 + 1e-7;
    const std::vector<Case> cases = {
        {"vsm", {"kernel=5", "filter=box"}, 1e-5},
        {"vsm", {"kernel=4", "filter=gaussian"}, 1e-5},   // even: taps between texels
        {"vsm", {"kernel=1"}, 1e-5},                      // no blur: the moments alone
        {"vsm", {"kernel=31", "filter=box", "mipmaps=true"}, 1e-5},
        {"vsm", {"kernel=5", "derivative_moment=true"}, 1e-5},   // rendered moments, blurred in compute
        // Partial work groups at the map's edges. At power-of-two sizes both paths agree to float
        // rounding; at 1000 they differ by up to 1.9e-5 on llvmpipe, and it is the fragment path
        // that is off (ComputeBlurIsTheSeparableFilterOfTheUnblurredMap): its bilinear lookups at
        // (i + 0.5 + x) / 1000 miss the texel centres by a rounding error that llvmpipe's weights
        // resolve (8-bit sub-texel weights would round it away; not checked on a GPU).
        {"vsm", {"kernel=7", "resolution=1000"}, 5e-5},
        {"esm", {"kernel=5"}, 1e-5},
        {"esm", {"kernel=8", "filter=gaussian"}, 1e-5},
        {"evsm", {"kernel=5"}, 1e-5},
        {"evsm", {"kernel=13", "filter=gaussian"}, 1e-5},
        {"msm", {"kernel=5", "storage=rgba32f"}, 1e-5},
        {"msm", {"kernel=10", "filter=gaussian", "storage=rgba32f"}, 1e-5},
        {"msm", {"kernel=5", "storage=rgba16"}, rgba16Level},
        {"msm", {"kernel=1", "storage=rgba16"}, rgba16Level},
    };
    for (const char* scene : {"cube", "contact"}) {
        load(scene);
        for (const Case& c : cases) {
            std::string label = std::string(c.technique) + " on " + scene;
            for (const auto& set : c.sets) label += " " + set;
            SCOPED_TRACE(label);
            auto with = [&](const char* blur) {
                // 512 texels unless the case says otherwise: a quarter of the fast map's, llvmpipe's compute is slow.
                std::vector<std::string> sets = {"resolution=512"};
                sets.insert(sets.end(), c.sets.begin(), c.sets.end());
                sets.push_back(std::string("blur=") + blur);
                render(c.technique, sets);
                return readMoments(*app_, c.technique);
            };
            const MomentTexture fragment = with("fragment");
            const MomentTexture compute = with("compute");
            ASSERT_EQ(compute.width, label.find("resolution=1000") != std::string::npos ? 1000 : 512);
            ASSERT_EQ(fragment.width, compute.width);
            // The map holds a shadow, not only empty texels.
            int occupied = 0;
            for (const glm::vec4& t : fragment.texels) occupied += t != fragment.texels.front();
            EXPECT_GT(occupied, 1000);
            const double worst = largestDifference(fragment, compute);
            std::printf("%s: compute vs fragment blur, largest difference %.3g\n", label.c_str(), worst);
            EXPECT_LE(worst, c.tolerance);
        }
    }
}

// The separable filter of separable_blur.frag/.comp on the CPU: N taps at i - (N - 1) / 2, an even
// kernel's taps the mean of the two texels they fall between, clamped to the edge; x, then y.
MomentTexture blurOnCpu(const MomentTexture& in, int kernel, bool gaussian) {
    const float half = 0.5f * float(kernel - 1), sigma = std::max(float(kernel) / 6.0f, 1e-3f);
    auto pass = [&](const MomentTexture& src, glm::ivec2 axis) {
        MomentTexture out = src;
        for (int y = 0; y < src.height; ++y)
            for (int x = 0; x < src.width; ++x) {
                glm::vec4 sum(0.0f);
                float weightSum = 0.0f;
                for (int i = 0; i < kernel; ++i) {
                    const float t = float(i) - half;
                    const float w = gaussian ? std::exp(-0.5f * t * t / (sigma * sigma)) : 1.0f;
                    const int left = int(std::floor(t));
                    const glm::ivec2 p = glm::ivec2(x, y) + axis * left;
                    glm::vec4 tap = src.fetch(p.x, p.y);
                    if (t != float(left)) tap = (tap + src.fetch(p.x + axis.x, p.y + axis.y)) * 0.5f;
                    sum += w * tap;
                    weightSum += w;
                }
                out.texels[size_t(y) * size_t(src.width) + size_t(x)] = sum / weightSum;
            }
        return out;
    };
    return pass(pass(in, {1, 0}), {0, 1});
}

TEST_F(MomentShadows, ComputeBlurIsTheSeparableFilterOfTheUnblurredMap) {
    // At a size that is not a power of two (partial work groups along both axes), the compute path
    // against the filter applied on the CPU to the unblurred map of the same frame.
    load("contact");
    for (const auto& [kernel, gaussian] : {std::pair{7, false}, std::pair{6, true}}) {
        SCOPED_TRACE(std::to_string(kernel) + (gaussian ? " gaussian" : " box"));
        const std::vector<std::string> map = {"resolution=1000", gaussian ? "filter=gaussian" : "filter=box"};
        auto with = [&](std::vector<std::string> sets) {
            sets.insert(sets.begin(), map.begin(), map.end());
            render("vsm", sets);
            return readMoments(*app_, "vsm");
        };
        const MomentTexture unblurred = with({"kernel=1", "blur=fragment"});
        const MomentTexture expected = blurOnCpu(unblurred, kernel, gaussian);
        const double compute = largestDifference(expected, with({"kernel=" + std::to_string(kernel), "blur=compute"}));
        const double fragment = largestDifference(expected, with({"kernel=" + std::to_string(kernel), "blur=fragment"}));
        std::printf("vsm at 1000 texels, kernel %d: largest difference from the CPU filter, compute %.3g, fragment %.3g\n",
                    kernel, compute, fragment);
        EXPECT_LE(compute, 1e-6);
    }
}

TEST_F(MomentShadows, BothBlurPathsUseTheSameTrackedMemoryAndTimeTheirPasses) {
    load("cube");
    std::string error;
    // The passes each path times: without a blur, the compute path still derives the moments from
    // the depth in a pass of its own ("moments"); the fragment path renders them and is done.
    auto passes = [&](const std::string& technique) {
        app_->timer().drain();
        app_->timer().clearHistory();
        EXPECT_TRUE(app_->renderFrame(technique, error)) << error;
        app_->timer().drain();
        std::set<std::string> names;
        for (const auto& [name, times] : app_->timer().history()) names.insert(name);
        return names;
    };
    for (const char* technique : kMomentTechniques) {
        SCOPED_TRACE(technique);
        size_t bytes[2] = {};
        for (int path = 0; path < 2; ++path) {
            ASSERT_TRUE(app_->applyAssignments({"resolution=512", "kernel=5", path ? "blur=compute" : "blur=fragment"},
                                               technique, error))
                << error;
            ASSERT_TRUE(app_->renderFrame(technique, error)) << error;
            bytes[path] = app_->techniques().get(technique, error)->host().gpuBytes();
            EXPECT_TRUE(passes(technique).count("blur"));
            ASSERT_TRUE(app_->applyAssignments({"kernel=1"}, technique, error)) << error;
            const auto unblurred = passes(technique);
            EXPECT_TRUE(unblurred.count("shadow map"));
            EXPECT_FALSE(unblurred.count("blur"));
            EXPECT_EQ(unblurred.count("moments"), size_t(path)) << (path ? "compute" : "fragment");
        }
        EXPECT_EQ(bytes[0], bytes[1]) << "the depth buffer, the map and its scratch texture on both paths";
    }
}

// ---------------------------------------------------------------------------------------------
// Memory and accuracy

TEST_F(MomentShadows, MemoryIsAccountedAndReleasedWhenParametersChange) {
    load("cube");
    std::string error;
    auto bytes = [&](const std::string& technique, const std::vector<std::string>& sets) {
        EXPECT_TRUE(app_->applyAssignments(sets, technique, error)) << error;
        EXPECT_TRUE(app_->renderFrame(technique, error)) << error;
        return app_->techniques().get(technique, error)->host().gpuBytes();
    };
    const size_t n = 512 * 512;
    // The uniform blocks (tracked buffers): the map's, the blur's two and the technique's own (16 bytes each).
    const size_t b = sizeof(kit::MomentMapUniforms) + 2 * sizeof(kit::BlurUniforms) + 16;
    // Moments + depth buffer, plus a scratch texture of the moments' format when blurring.
    EXPECT_EQ(bytes("vsm", {"resolution=512", "kernel=1", "mipmaps=false"}) - b, n * (8 + 4));
    EXPECT_EQ(bytes("vsm", {"resolution=512", "kernel=5", "mipmaps=false"}) - b, n * (8 + 4 + 8));
    size_t mipTexels = 0;
    for (int size = 512; size >= 1; size /= 2) mipTexels += size_t(size) * size_t(size);
    EXPECT_EQ(bytes("vsm", {"resolution=512", "kernel=5", "mipmaps=true"}) - b, mipTexels * 8 + n * (4 + 8));
    EXPECT_EQ(bytes("esm", {"resolution=512", "kernel=5", "mipmaps=false"}) - b, n * (4 + 4 + 4));
    EXPECT_EQ(bytes("evsm", {"resolution=512", "kernel=5", "mipmaps=false"}) - b - 16, n * (16 + 4 + 16))
        << "evsm's own block is 32 bytes";
    EXPECT_EQ(bytes("msm", {"resolution=512", "kernel=5", "mipmaps=false", "storage=rgba32f"}) - b, n * (16 + 4 + 16));
    EXPECT_EQ(bytes("msm", {"resolution=512", "kernel=5", "mipmaps=false", "storage=rgba16"}) - b, n * (8 + 4 + 8))
        << "16-bit quantised storage halves the moments";
}

TEST_F(MomentShadows, AccuracyAgainstTheHardReferenceOnCube) {
    // Stated bounds: on cube at 320x240 with a 1024 map and a 5-tap blur, against the hard reference
    // (these techniques antialias, they do not soften physically, so the penumbra error is the blur
    // itself, about 0.3 per penumbra pixel). Measured: MAE 0.0023-0.0028, outside the penumbra
    // 0.0007-0.0011, false shadow and false light 0.0001-0.0005.
    load("cube");
    for (const char* technique : kMomentTechniques) {
        SCOPED_TRACE(technique);
        const AccuracyMetrics m = test::measureAccuracy(*app_, technique, withFastMap({"kernel=5"}), Mode::Hard);
        EXPECT_LT(m.mae, 0.004);
        EXPECT_LT(m.maeOutsidePenumbra, 0.002) << "no acne, no leaks away from the edges";
        EXPECT_LT(m.falseShadowRate, 0.002);
        EXPECT_LT(m.falseLightRate, 0.002);
        EXPECT_GT(m.comparedFraction, 0.5);
    }
}

TEST_F(MomentShadows, VsmDerivativeBasedSecondMomentRemovesSelfShadowing) {
    // Without the minimum variance and without blur, a surface's own moments have zero variance and
    // the bound flips with the rounding of the depth: acne on the ground. Eq. 3.16 adds the variance
    // of the depth's slope across a texel, a slope-scaled bias.
    load("cube");
    for (const glm::vec3 direction : {glm::vec3(-1.0f, -0.105f, -0.2f), glm::vec3(0.3f, -1.0f, 0.2f)}) {
        SCOPED_TRACE(direction.y);
        app_->light().direction = glm::normalize(direction);
        const AccuracyMetrics acne = test::measureAccuracy(
            *app_, "vsm", withFastMap({"kernel=1", "min_variance=0", "derivative_moment=false"}), Mode::Hard);
        const AccuracyMetrics biased = test::measureAccuracy(
            *app_, "vsm", withFastMap({"kernel=1", "min_variance=0", "derivative_moment=true"}), Mode::Hard);
        std::printf("vsm without variance floor: outside-penumbra error %.4f, with eq. 3.16 %.4f\n",
                    acne.maeOutsidePenumbra, biased.maeOutsidePenumbra);
        EXPECT_GT(acne.maeOutsidePenumbra, 0.004) << "acne without any bias";
        EXPECT_LT(biased.maeOutsidePenumbra, 0.002);
        EXPECT_LT(biased.falseShadowRate, acne.falseShadowRate);
    }
}

} // namespace

// Stated bounds against the soft reference on the three test scenes (320x240, 32 rays per
// pixel). Measured MAE, cube/contact/overlap: vsm 0.0021/0.0036/0.0082, esm 0.0023/0.0036/0.0082,
// evsm 0.0025/0.0041/0.0070, msm 0.0020/0.0038/0.0052; false rates all below 0.1%. Bounds are
// about 1.5x those, so a regression shows and sampling noise does not.
class MomentSoftAccuracy : public ::testing::TestWithParam<std::string> {};

TEST_P(MomentSoftAccuracy, WithinStatedBoundsOfTheSoftReference) {
    const std::string scene = GetParam();
    auto app = test::makeHeadlessApp(scene, {320, 240});
    ASSERT_TRUE(app);
    const double bound = scene == "cube" ? 0.004 : scene == "contact" ? 0.0065 : 0.0125;
    for (const char* technique : {"vsm", "esm", "evsm", "msm"}) {
        SCOPED_TRACE(technique);
        const AccuracyMetrics m = test::measureAccuracy(*app, technique, {}, ReferenceOptions::Mode::Soft, 32);
        EXPECT_LT(m.mae, bound);
        EXPECT_LT(m.falseShadowRate, 0.0015);
        EXPECT_LT(m.falseLightRate, 0.0015);
    }
}

// The accuracy condition for the compute path: soft MAE within 5% of the fragment path's.
TEST_P(MomentSoftAccuracy, ComputeBlurWithinFivePercentOfTheFragmentBlur) {
    const std::string scene = GetParam();
    auto app = test::makeHeadlessApp(scene, {320, 240});
    ASSERT_TRUE(app);
    for (const char* technique : {"vsm", "esm", "evsm", "msm"}) {
        SCOPED_TRACE(technique);
        const double fragment =
            test::measureAccuracy(*app, technique, {"blur=fragment"}, ReferenceOptions::Mode::Soft, 32).mae;
        const double compute =
            test::measureAccuracy(*app, technique, {"blur=compute"}, ReferenceOptions::Mode::Soft, 32).mae;
        std::printf("%s on %s: soft MAE fragment %.6f, compute %.6f\n", technique, scene.c_str(), fragment, compute);
        EXPECT_LE(std::abs(compute - fragment), 0.05 * fragment);
    }
}

INSTANTIATE_TEST_SUITE_P(TestScenes, MomentSoftAccuracy, ::testing::Values("cube", "contact", "overlap"));
