// The host's screen-space contact shadows (issue 30; host_shared/contact_shadows_shared.h,
// render/renderer.h contactShadows, plugin/host_params.h host.contact_*) and the contact band
// they are judged in (groundtruth/contact_band.h), on OSMesa (llvmpipe).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>

#include "bench/stress.h"
#include "test_support.h"

using namespace shadowlab;

namespace {

// shadowmap with a bias large enough to lift its shadows off their casters (peter panning): a
// 16-bit map pushed 1000 steps plus a steep slope term.
const std::vector<std::string> kPeterPanned = {"depth_format=16", "constant_bias=1000", "slope_bias=16"};

std::vector<std::string> withContact(std::vector<std::string> sets, const std::string& length) {
    sets.push_back("host.contact_shadows=" + length);
    return sets;
}

float scalar(glm::vec3 v) { return (v.r + v.g + v.b) / 3.0f; }

struct ContactFrames {
    Evaluation off, on;
};

ContactFrames offAndOn(App& app, const std::string& technique, const std::vector<std::string>& sets, const std::string& length) {
    ContactFrames f;
    f.off = test::evaluateTechnique(app, technique, withContact(sets, "0"), ReferenceOptions::Mode::Hard);
    f.on = test::evaluateTechnique(app, technique, withContact(sets, length), ReferenceOptions::Mode::Hard);
    return f;
}

} // namespace

// The band is where the hard reference is shadowed by a caster within kContactBandDistance: every
// band pixel must be in the reference's shadow, and `contact` (casters on and near the ground)
// must have a band of some size and a far class too.
TEST(ContactShadows, TheBandIsShadowedInTheReference) {
    auto app = test::makeHeadlessApp("contact", {320, 180});
    ASSERT_TRUE(app);
    const Evaluation e = test::evaluateTechnique(*app, "shadowmap", {}, ReferenceOptions::Mode::Hard);
    ASSERT_EQ(e.contactBand.size(), e.mask.size());
    size_t band = 0, far = 0, lit = 0;
    for (size_t i = 0; i < e.contactBand.size(); ++i) {
        EXPECT_TRUE(e.contactBand[i] == 0 || e.mask[i]) << "only compared pixels are classed";
        if (e.contactBand[i] == 1) {
            ++band;
            lit += scalar(e.reference[i]) >= 0.5f ? 1 : 0;
        }
        far += e.contactBand[i] == 2 ? 1 : 0;
    }
    std::printf("contact band on contact, 320x180: %zu band pixels, %zu far from contact\n", band, far);
    EXPECT_EQ(band, e.metrics.contactBandPixels);
    EXPECT_GT(band, 100u);
    EXPECT_GT(far, 10000u);
    EXPECT_EQ(lit, 0u) << "a band pixel's shadow ray meets an opaque caster: the reference is shadowed";
    // A soft reference has no band (the rate is against the hard one).
    const Evaluation soft = test::evaluateTechnique(*app, "shadowmap", {}, ReferenceOptions::Mode::Soft, 4);
    EXPECT_TRUE(soft.contactBand.empty());
}

// The point of the pass: under a peter-panned map the contact band of `contact` leaks light (the
// casters' feet lit); contact shadows must remove most of it, measured against the hard reference.
// Pixels far from any contact (no caster within 4 x the band distance along the light) keep their
// term: bit for bit except where the march's thickness assumption puts a false shadow behind a
// caster, which must stay rare.
TEST(ContactShadows, ReduceTheFalseLightAtContactAndLeaveTheRest) {
    auto app = test::makeHeadlessApp("contact", {320, 180});
    ASSERT_TRUE(app);
    const ContactFrames f = offAndOn(*app, "shadowmap", kPeterPanned, "0.75");
    const double off = f.off.metrics.contactFalseLightRate, on = f.on.metrics.contactFalseLightRate;
    size_t farPixels = 0, farChanged = 0;
    for (size_t i = 0; i < f.on.contactBand.size(); ++i) {
        if (f.on.contactBand[i] != 2) continue;
        ++farPixels;
        farChanged += f.on.technique[i] != f.off.technique[i] ? 1 : 0;
    }
    std::printf("contact, shadowmap peter-panned, 320x180: band false light %.4f off, %.4f with contact shadows 0.75; "
                "%zu of %zu far pixels changed\n",
                off, on, farChanged, farPixels);
    EXPECT_EQ(f.on.contactBand, f.off.contactBand) << "the band is the reference's, the same either way";
    EXPECT_GT(off, 0.2) << "the large bias must leak at the casters' feet, or the test shows nothing";
    EXPECT_LT(on, 0.5 * off) << "contact shadows at least halve the leak";
    EXPECT_LE(f.on.metrics.falseLightRate, f.off.metrics.falseLightRate) << "min() can only darken";
    ASSERT_GT(farPixels, 10000u);
    EXPECT_LT(double(farChanged), 0.002 * double(farPixels));
}

// host.contact_shadows = 0 is the frame as it was before the pass existed: no contact scope or
// forced camera pre-pass, and the colour and term bit-identical to a frame that never turned it
// on, also after frames that did (the main programs' switch is set every pass).
TEST(ContactShadows, OffIsTheFrameWithoutIt) {
    auto app = test::makeHeadlessApp("contact", {200, 120});
    ASSERT_TRUE(app);
    std::string error;
    auto frame = [&](const std::string& length) {
        EXPECT_TRUE(app->applyAssignments({"host.contact_shadows=" + length, "resolution=1024"}, "pcf", error)) << error;
        Measurement m;
        EXPECT_TRUE(app->measure("pcf", 0, 2, m, error)) << error;
        EXPECT_EQ(m.gpuMs.count("contact shadows") > 0, length != "0");
        EXPECT_EQ(m.gpuMs.count("contact pre-pass") > 0, length != "0") << "pcf asks for no camera pre-pass";
        return std::make_pair(test::readTarget(*app, MainTarget::Color), test::readTarget(*app, MainTarget::Visibility));
    };
    const auto [colour0, term0] = frame("0");
    const auto [colourOn, termOn] = frame("0.75");
    const auto [colourBack, termBack] = frame("0");
    ASSERT_EQ(colour0.size(), colourBack.size());
    EXPECT_EQ(std::memcmp(colour0.data(), colourBack.data(), colour0.size() * sizeof(glm::vec4)), 0);
    EXPECT_EQ(std::memcmp(term0.data(), termBack.data(), term0.size() * sizeof(glm::vec4)), 0);
    EXPECT_NE(std::memcmp(term0.data(), termOn.data(), term0.size() * sizeof(glm::vec4)), 0) << "on changes something";
    EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
}

// Point and spot lights march towards the light's position (and stop there): on `point-light` and
// `spotlight` the pass must find occluders, and under a peter-panned map must not add false light.
TEST(ContactShadows, PointAndSpotLights) {
    for (const char* scene : {"point-light", "spotlight"}) {
        SCOPED_TRACE(scene);
        auto app = test::makeHeadlessApp(scene, {240, 160});
        ASSERT_TRUE(app);
        const ContactFrames f = offAndOn(*app, "shadowmap", kPeterPanned, "0.75");
        // The contact term of the last frame: R8, 0 where the march found an occluder.
        const glm::ivec2 size = app->renderer().size();
        std::vector<float> contact(size_t(size.x) * size_t(size.y));
        glGetTextureImage(app->renderer().contactTexture(), 0, GL_RED, GL_FLOAT, GLsizei(contact.size() * sizeof(float)),
                          contact.data());
        size_t occluded = 0;
        for (const float c : contact) occluded += c < 0.5f ? 1 : 0;
        std::printf("contact shadows on %s with shadowmap: %zu occluded pixels; band false light %.4f off, %.4f on\n", scene,
                    occluded, f.off.metrics.contactFalseLightRate, f.on.metrics.contactFalseLightRate);
        EXPECT_GT(occluded, 50u);
        EXPECT_LE(f.on.metrics.contactFalseLightRate, f.off.metrics.contactFalseLightRate);
    }
}

// Bad values are refused naming the parameter (the CLI's exit 2 is in cli_errors.sh).
TEST(ContactShadows, ParametersAreChecked) {
    auto app = test::makeHeadlessApp("cube", {64, 48});
    ASSERT_TRUE(app);
    std::string error;
    for (const char* bad : {"host.contact_shadows=-1", "host.contact_shadows=101", "host.contact_thickness=0",
                            "host.contact_steps=0", "host.contact_steps=65", "host.contact_jitter=2"}) {
        EXPECT_FALSE(app->applyAssignments({bad}, "shadowmap", error)) << bad;
        const std::string name = std::string(bad).substr(5, std::string(bad).find('=') - 5);
        EXPECT_NE(error.find(name), std::string::npos) << error;
    }
    EXPECT_TRUE(app->applyAssignments({"host.contact_shadows=0.5", "host.contact_steps=64"}, "shadowmap", error)) << error;
}

// The stress cases' claims, measured: the plate seen face on is shadowed again at its foot; the
// same foot with the plate outside the view, or the plate seen edge on, keeps the peter-panned
// map's leak (the failure the cases claim, detected as a failed cell where the claim says fail).
TEST(ContactShadows, StressCasesFailWhereTheyClaim) {
    StressSuite suite;
    std::string error;
    ASSERT_TRUE(loadStressSuite(defaultStressCases(), suite, error)) << error;
    auto app = test::makeHeadlessApp("cube", suite.size);
    ASSERT_TRUE(app);
    for (const char* id : {"contact-shadows-plate", "contact-shadows-offscreen", "contact-shadows-edge-on"}) {
        const auto c = std::find_if(suite.cases.begin(), suite.cases.end(), [&](const StressCase& s) { return s.id == id; });
        ASSERT_NE(c, suite.cases.end()) << id;
        StressCell cell;
        ASSERT_TRUE(runStressCell(*app, suite, *c, "shadowmap", {}, cell, error)) << error;
        std::printf("stress %-26s shadowmap %s: contact_false_light %.4f over %zu band pixels (threshold %.2f) %s\n", id,
                    cell.settings.c_str(), cell.value, cell.contactBandPixels, c->threshold, cell.pass ? "pass" : "FAIL");
        EXPECT_GT(cell.contactBandPixels, 100u) << id;
        EXPECT_EQ(cell.pass, !cell.expectedFail) << id << ": the verdict the case claims";
        EXPECT_NE(cell.settings.find("host.contact_shadows="), std::string::npos);
        // Without contact shadows every one of them leaks: the pass is what makes the difference.
        StressOptions off;
        off.sets = {"host.contact_shadows=0"};
        StressCell without;
        ASSERT_TRUE(runStressCell(*app, suite, *c, "shadowmap", off, without, error)) << error;
        EXPECT_FALSE(without.pass) << id;
        EXPECT_GE(without.value, cell.value) << id;
    }
    EXPECT_EQ(app->hostValues()[kHostContactShadows], 0.0) << "a case's host settings end with its cell";
}
