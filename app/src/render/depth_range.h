// The depth range a shadow map holds, for its debug image (issue 29): the `shadow map` view maps
// [nearest, farthest] stored depth to black..white instead of [0, 1], where a map's depths often
// sit in a few hundredths near 1 and show as a flat white. Texels at the clear value (1, nothing
// stored) are left out. In the window the texels come back through a pixel-pack buffer polled
// frames later (never waited for), measured again every kEveryFrames frames the view is shown;
// headless commands measure at once.
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "gl/gl.h"
#include "render/texture_readback.h"

namespace shadowlab {

class DepthRange {
public:
    static constexpr int kEveryFrames = 30;
    // [lo, hi] of `texture` as last measured; {0, 1} until it has been.
    glm::vec2 range(GLuint texture) const { return texture == measured_ ? range_ : glm::vec2(0.0f, 1.0f); }
    // GL thread, each frame the image is shown: takes a finished readback, starts the next.
    void update(GLuint texture);
    // GL thread, at once (the CPU waits for the GPU: headless commands only).
    void measureNow(GLuint texture);
    // The range of texels below the clear value; {0, 1} when none is.
    static glm::vec2 rangeOf(const std::vector<float>& texels);

private:
    bool describe(GLuint texture, glm::ivec2& size, GLenum& format) const;
    PixelBufferReadback readback_;
    std::vector<float> texels_;
    GLuint measured_ = 0, pending_ = 0;
    glm::vec2 range_{0.0f, 1.0f};
    int frames_ = 0;
};

} // namespace shadowlab
