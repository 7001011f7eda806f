// Helpers shared by the GL tests: a headless App on OSMesa (the CI backend) and pixel access.
#pragma once

#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "app.h"

namespace shadowlab::test {

// Headless App on OSMesa with the given scene; fails the test (and returns nullptr) otherwise.
inline std::unique_ptr<App> makeHeadlessApp(const std::string& scene, glm::ivec2 size = {320, 240},
                                            std::optional<glm::vec3> lightDirection = std::nullopt) {
    auto app = std::make_unique<App>();
    AppOptions options;
    options.scene = scene;
    options.size = size;
    options.backend = BackendKind::OSMesa;
    options.lightDirection = lightDirection;
    std::string error;
    bool badInput = false;
    if (!app->init(options, false, error, badInput)) {
        ADD_FAILURE() << "App init failed: " << error;
        return nullptr;
    }
    return app;
}

// Renders `technique` and returns the visibility target (rgb shadow term, a = compared mask).
inline std::vector<glm::vec4> renderVisibility(App& app, const std::string& technique,
                                               const std::vector<std::string>& sets = {}) {
    std::string error;
    EXPECT_TRUE(app.applyAssignments(sets, technique, error)) << error;
    EXPECT_TRUE(app.renderFrame(technique, error)) << error;
    return app.renderer().readTarget(MainTarget::Visibility);
}

} // namespace shadowlab::test
