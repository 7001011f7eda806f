// What the filterable shadow maps' passes are asked for (kit/moment_map.h, kit/cube_moment_map.h).
#pragma once

#include <glad/gl.h>
#include <glm/glm.hpp>

#include "shadowlab/kit/focus.h"

namespace shadowlab::kit {

enum class BlurPath : int { Fragment = 0, Compute = 1 };   // the `blur` parameter's values

struct MomentMapConfig {
    int resolution = 1024;
    GLenum format = GL_RG32F;    // GL_R32F, GL_RG32F, GL_RGBA32F or GL_RGBA16 (unorm)
    bool mipmaps = false;        // trilinear lookups; mipmaps are rebuilt after the blur
    int kernelSize = 1;          // taps per direction; 1 = no blur
    bool gaussian = false;       // blur weights: false box, true Gaussian (sigma = kernel / 6)
    glm::vec4 clearValue{1.0f};  // moments of an empty texel: depth 1, nothing occludes there (the
                                 // fragment path clears to it; the compute path derives it from the
                                 // cleared depth 1, so it must equal momentsFromDepth(1))
    BlurPath blur = BlurPath::Compute;
    bool momentsNeedDerivatives = false;   // momentsFromDepth uses dFdx/dFdy now: the moments are
                                           // rendered as colour on both paths (blurred in compute)
    FitConfig fit{};             // the `fit` and `snap` parameters; default: the whole scene
};

} // namespace shadowlab::kit
