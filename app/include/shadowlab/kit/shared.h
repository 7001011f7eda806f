// One declaration of the data that C++ and GLSL share: uniform blocks and texture units.
// A technique writes a header that both its .cpp and its .glsl include, e.g.
//
//   #include "shadowlab/kit/shared.h"
//   SHADOWLAB_SHARED_BEGIN(pcf)
//   SHADOWLAB_TEXTURE_UNIT(kShadowMapUnit, 4)
//   SHADOWLAB_UNIFORM_BLOCK(PcfUniforms, 2) {
//       int uKernel;
//       float uOffsetScale;
//       float uConeBias;
//       float uPad;
//   };
//   SHADOWLAB_SHARED_END
//
// In GLSL the block is `layout(std140, binding = 2) uniform PcfUniforms {...};` (members read by
// name) and the unit a constant for `layout(binding = kShadowMapUnit)`; in C++ the block is a
// struct in namespace shadowlab::shared::pcf for kit::UniformBlock<PcfUniforms> and the unit a
// constexpr. Only types whose std140 layout equals C++'s exist on the C++ side (mat4, vec4,
// ivec4, uvec4, float, int, uint), so a member that would be laid out differently does not compile.
// Bindings: 0 is the host's frame block; 1 the kit's depth or moment map; 2+ the technique's.
// Texture units 0-3 are the host's; 4+ the technique's. Image units (SHADOWLAB_IMAGE_UNIT, for
// imageLoad/imageStore): 0 is the kit moment map's compute blur; 1+ the technique's.
#ifndef SHADOWLAB_KIT_SHARED_H
#define SHADOWLAB_KIT_SHARED_H

#ifdef __cplusplus
#include <cstdint>
#include <type_traits>

#include <glm/glm.hpp>

namespace shadowlab::glsl {
using mat4 = glm::mat4;
using vec4 = glm::vec4;
using ivec4 = glm::ivec4;
using uvec4 = glm::uvec4;
using uint = uint32_t;
} // namespace shadowlab::glsl

#define SHADOWLAB_SHARED_BEGIN(name) namespace shadowlab::shared::name { using namespace shadowlab::glsl;
#define SHADOWLAB_SHARED_END }
#define SHADOWLAB_TEXTURE_UNIT(name, unit) inline constexpr uint32_t name = unit;
#define SHADOWLAB_IMAGE_UNIT(name, unit) inline constexpr uint32_t name = unit;
#define SHADOWLAB_UNIFORM_BLOCK(Name, bindingPoint) struct alignas(16) Name : ::shadowlab::glsl::Binding<bindingPoint>

namespace shadowlab::glsl {
// Empty base carrying the block's binding point (no storage: the layout stays std140's).
template <uint32_t bindingPoint> struct Binding {
    static constexpr uint32_t kBinding = bindingPoint;
};
} // namespace shadowlab::glsl

#else
#define SHADOWLAB_SHARED_BEGIN(name)
#define SHADOWLAB_SHARED_END
#define SHADOWLAB_TEXTURE_UNIT(name, unit) const int name = unit;
#define SHADOWLAB_IMAGE_UNIT(name, unit) const int name = unit;
#define SHADOWLAB_UNIFORM_BLOCK(Name, bindingPoint) layout(std140, binding = bindingPoint) uniform Name
#endif

#endif
