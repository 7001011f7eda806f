// Rendered pixels against analytic shadows on the `cube` scene: the shadow of a box on a plane
// under a directional light is the set of ground points whose ray towards the light hits the box.
#include <gtest/gtest.h>

#include <algorithm>

#include "shadowlab/kit/depth_map_shared.h"
#include "shadowlab/kit/layered_depth_shared.h"
#include "test_support.h"
#include "util/paths.h"

using namespace shadowlab;

class CubeScene : public ::testing::Test {
protected:
    void SetUp() override {
        app_ = test::makeHeadlessApp("cube", {320, 240});
        ASSERT_TRUE(app_);
    }
    std::unique_ptr<App> app_;
};

TEST_F(CubeScene, ShadowMapDarkensTheAnalyticShadowAndNothingElse) {
    const auto visibility = test::renderVisibility(*app_, "shadowmap");
    const test::GroundClassification ground = test::classifyGround(*app_);
    int inside = 0, outside = 0, wrongInside = 0, wrongOutside = 0;
    for (int y = 0; y < ground.size.y; ++y)
        for (int x = 0; x < ground.size.x; ++x) {
            const size_t i = size_t(y) * size_t(ground.size.x) + size_t(x);
            if (ground.analytic[i] < 0 || ground.nearBoundary(x, y, 2)) continue;
            const bool shadowed = visibility[i].r < 0.5f;
            if (ground.analytic[i] == 1) {
                ++inside;
                wrongInside += !shadowed;
            } else {
                ++outside;
                wrongOutside += shadowed;
            }
        }
    EXPECT_GT(inside, 500) << "the shadow must be in view";
    EXPECT_GT(outside, 5000);
    EXPECT_EQ(wrongInside, 0) << "lit pixels inside the analytic shadow polygon";
    EXPECT_EQ(wrongOutside, 0) << "shadowed pixels well outside it";
}

TEST_F(CubeScene, PlanarAgreesWithShadowMapOnTheGround) {
    const auto shadowMap = test::renderVisibility(*app_, "shadowmap", {"resolution=4096"});
    const auto planar = test::renderVisibility(*app_, "planar");
    const test::GroundClassification ground = test::classifyGround(*app_);
    int groundPixels = 0, disagreements = 0, planarInside = 0, planarWrongInside = 0;
    for (size_t i = 0; i < planar.size(); ++i) {
        if (ground.analytic[i] < 0) continue;
        ++groundPixels;
        disagreements += (planar[i].r < 0.5f) != (shadowMap[i].r < 0.5f);
        if (ground.analytic[i] == 1) {
            ++planarInside;
            planarWrongInside += planar[i].r >= 0.5f;
        }
    }
    ASSERT_GT(groundPixels, 10000);
    EXPECT_LT(double(disagreements), 0.01 * groundPixels) << disagreements << " of " << groundPixels;
    EXPECT_LT(double(planarWrongInside), 0.02 * planarInside) << "planar is exact up to edge pixels";
}

TEST_F(CubeScene, NoneHasNoShadowedPixels) {
    const auto visibility = test::renderVisibility(*app_, "none");
    int compared = 0;
    for (const auto& v : visibility) {
        if (v.a < 0.5f) continue;
        ++compared;
        EXPECT_EQ(v.r, 1.0f);
    }
    EXPECT_GT(compared, 10000);
}

TEST_F(CubeScene, PlanarHandlesAPointLightBelowTheCasterTop) {
    // A point light lower than the cube's top: the top projects "through" the light, towards the
    // far side of the light (the anti-shadow of seed 000 Fig. 3.3). The real shadow of the part
    // below the light falls on the side away from the light; nothing may darken beyond the light.
    app_->light().type = LightType::Point;
    app_->light().position = {2.5f, 0.6f, 0.0f};
    const auto planar = test::renderVisibility(*app_, "planar");
    const auto positions = test::readTarget(*app_, MainTarget::Position);
    int beyondLight = 0, behindCube = 0;
    for (size_t i = 0; i < positions.size(); ++i) {
        if (positions[i].w < 0.5f || std::abs(positions[i].y) > 1e-3f) continue;
        if (positions[i].x > 3.0f) beyondLight += planar[i].r < 0.5f;
        if (positions[i].x < -0.6f && std::abs(positions[i].z) < 0.4f) behindCube += planar[i].r < 0.5f;
    }
    EXPECT_EQ(beyondLight, 0) << "anti-shadow pixels";
    EXPECT_GT(behindCube, 50) << "the real shadow is there";
}

TEST_F(CubeScene, ShadowMapMemoryIsAccounted) {
    std::string error;
    ASSERT_TRUE(app_->applyAssignments({"resolution=1024", "depth_format=32F"}, "shadowmap", error)) << error;
    ASSERT_TRUE(app_->renderFrame("shadowmap", error)) << error;
    // The map and the blocks of kit::LayeredDepthMap: the first and second layers' depth-map blocks
    // and its own (the second layer's texture only when a two-layer bias_method asks for it).
    const size_t block = 2 * sizeof(shared::depth_map::DepthMapUniforms) + sizeof(shared::layered_depth::LayeredDepthUniforms);
    EXPECT_EQ(app_->techniques().get("shadowmap", error)->host().gpuBytes(), size_t(1024) * 1024 * 4 + block);
    ASSERT_TRUE(app_->applyAssignments({"resolution=512", "depth_format=16"}, "shadowmap", error)) << error;
    ASSERT_TRUE(app_->renderFrame("shadowmap", error)) << error;
    EXPECT_EQ(app_->techniques().get("shadowmap", error)->host().gpuBytes(), size_t(512) * 512 * 2 + block)
        << "the old map is released when the resolution changes";
}

TEST(Msaa, MultisampledMainPassResolvesAndStillShadowsTheCube) {
    auto app = std::make_unique<App>();
    AppOptions options;
    options.scene = "cube";
    options.size = {320, 240};
    options.backend = BackendKind::OSMesa;
    options.msaaSamples = 4;
    std::string error;
    bool badInput = false;
    ASSERT_TRUE(app->init(options, false, error, badInput)) << error;
    EXPECT_EQ(app->renderer().msaaSamples(), 4);
    const auto visibility = test::renderVisibility(*app, "shadowmap");
    const test::GroundClassification ground = test::classifyGround(*app);
    int inside = 0, dark = 0;
    for (size_t i = 0; i < visibility.size(); ++i) {
        if (ground.analytic[i] != 1 || ground.nearBoundary(int(i % 320), int(i / 320), 3)) continue;
        ++inside;
        dark += visibility[i].r < 0.5f;
    }
    EXPECT_GT(inside, 500);
    EXPECT_EQ(dark, inside);
    EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
    ASSERT_TRUE(app->presentView("shadowmap", {}, ~0u, {}, error)) << error;
    const Image image = app->readDisplay();
    EXPECT_EQ(image.width, 320);
}

// ABI 3 drawing: DrawRequest's order and culling planes, through the renderer the host services
// use. Object ids are drawn with the camera pre-pass's fragment stage into the pre-pass targets.
namespace {
struct IdDrawing {
    App& app;
    GLuint program = 0, fbo = 0;
    explicit IdDrawing(App& a) : app(a) {
        app.renderer().cameraPrepass();   // allocates the targets (and fills them depth-tested)
        ShaderRequest request;
        request.vertexFile = "main.vert";
        request.fragmentFile = "camera_prepass.frag";
        request.searchPaths = hostShaderPaths();
        std::string error;
        id_ = app.shaders().build(request, error);
        EXPECT_NE(id_, 0u) << error;
        program = app.shaders().program(id_);
        const CameraPrepass& t = app.renderer().prepassTargets();
        glCreateFramebuffers(1, &fbo);
        glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, t.position, 0);
        glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT1, t.normal, 0);
        glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT2, t.objectId, 0);
        const GLenum buffers[] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2};
        glNamedFramebufferDrawBuffers(fbo, 3, buffers);
    }
    ~IdDrawing() {
        glDeleteFramebuffers(1, &fbo);
        app.shaders().release(id_);
    }
    std::vector<uint32_t> ids() const {
        const glm::ivec2 size = app.renderer().size();
        std::vector<uint32_t> out(size_t(size.x) * size_t(size.y));
        glGetTextureImage(app.renderer().prepassTargets().objectId, 0, GL_RED_INTEGER, GL_UNSIGNED_INT,
                          GLsizei(out.size() * 4), out.data());
        return out;
    }
    // Draws `request` without depth test: the last object drawn wins every pixel it covers.
    std::vector<uint32_t> drawLastWins(const DrawRequest& request) {
        app.renderer().applyDefaultState();
        glBindFramebuffer(GL_FRAMEBUFFER, fbo);
        const GLuint zero[4] = {0, 0, 0, 0};
        glClearNamedFramebufferuiv(fbo, GL_COLOR, 2, zero);
        glDisable(GL_DEPTH_TEST);
        app.renderer().drawScene(request, program);
        return ids();
    }
    ProgramId id_ = 0;
};
} // namespace

TEST_F(CubeScene, DrawRequestsSortByDistanceAndCullByPlanes) {
    std::string error;
    ASSERT_TRUE(app_->renderFrame("none", error)) << error;
    IdDrawing drawing(*app_);
    const std::vector<uint32_t> visible = drawing.ids();   // depth-tested: what the camera sees
    uint32_t cubeId = 0;
    for (uint32_t i = 0; i < app_->scene().objects.size(); ++i)
        if (app_->scene().objects[i].name == "cube") cubeId = i + 1;
    ASSERT_NE(cubeId, 0u);
    const size_t cubePixels = size_t(std::count(visible.begin(), visible.end(), cubeId));
    ASSERT_GT(cubePixels, 100u);
    const glm::vec3 eye = app_->renderer().camera().position;
    auto countOnCube = [&](const std::vector<uint32_t>& ids, uint32_t id) {
        size_t n = 0;
        for (size_t i = 0; i < ids.size(); ++i) n += visible[i] == cubeId && ids[i] == id;
        return n;
    };
    DrawRequest backToFront;
    backToFront.order = DrawOrder::BackToFront;
    backToFront.orderReference = glm::vec4(eye, 1.0f);
    EXPECT_EQ(countOnCube(drawing.drawLastWins(backToFront), cubeId), cubePixels)
        << "back to front from the eye: the cube, nearer, is drawn last";
    DrawRequest frontToBack = backToFront;
    frontToBack.order = DrawOrder::FrontToBack;
    EXPECT_LT(countOnCube(drawing.drawLastWins(frontToBack), cubeId), cubePixels / 10)
        << "front to back: the ground, farther, is drawn over the cube";
    // A plane that keeps only what lies above y = 0.5 (the cube reaches higher, the ground does not).
    const glm::vec4 above{0.0f, 1.0f, 0.0f, -0.5f};
    DrawRequest culled;
    culled.cullPlanes = &above;
    culled.cullPlaneCount = 1;
    const std::vector<uint32_t> culledIds = drawing.drawLastWins(culled);
    EXPECT_EQ(countOnCube(culledIds, cubeId), cubePixels) << "the cube passes";
    EXPECT_EQ(size_t(std::count_if(culledIds.begin(), culledIds.end(), [&](uint32_t id) { return id != 0 && id != cubeId; })),
              0u) << "only the cube is drawn";
    EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
}
