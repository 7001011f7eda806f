// shadowlab plugin API: the whole boundary between the host and a shadow technique.
//
// A technique is a shared library under plugins/<id>/ exporting one extern "C" function,
// shadowlab_plugin_entry(), which returns a static PluginEntry. The host reads abiVersion before it
// calls anything else and refuses a mismatch (CLAP's clap_version_is_compatible), then reads the
// static TechniqueDesc (no GL needed: `shadowlab list` never creates a technique), then creates the
// technique and calls init() with a GL context current and a host-services table.
//
// A frame, as the host drives it:
//   technique.renderShadows(params)     shadow maps, filtering passes (wrapped in GpuPass scopes)
//   host main pass                      forward Blinn-Phong; the technique's GLSL function
//                                       `vec3 shadowTerm(ShadowInput s)` (file named by
//                                       TechniqueDesc::shadowGlsl) multiplies the direct light,
//                                       after technique.bindMainPass(program, params) set its
//                                       uniforms and textures.
//
// Parameters are declared once in the descriptor; the host owns their values (GUI, --set, sweeps,
// hot-reload hand-over) and passes them in. A plugin only reads them.
//
// Bump SHADOWLAB_ABI_VERSION whenever anything in this file changes layout or meaning.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include <glm/glm.hpp>

#define SHADOWLAB_ABI_VERSION 2u

namespace shadowlab {

// ---------------------------------------------------------------------------------------------
// Parameters
enum class ParamType : uint32_t { Float, Int, Bool, Enum };

struct ParamDesc {
    const char* id;            // stable key: --set id=value, sweeps, saved state
    const char* label;         // shown in the panel
    ParamType type;
    double minValue;
    double maxValue;
    double defaultValue;
    const char* unit;          // "" when dimensionless
    const char* help;          // what it does and what goes wrong at either end of its range
    const char* enumLabels;    // Enum only: "a|b|c", the value is the index
};

// Values of a technique's parameters, in descriptor order.
class ParamValues {
public:
    ParamValues(const double* values, uint32_t count) : values_(values), count_(count) {}
    double operator[](uint32_t index) const { return index < count_ ? values_[index] : 0.0; }
    float asFloat(uint32_t index) const { return static_cast<float>((*this)[index]); }
    int asInt(uint32_t index) const { return static_cast<int>((*this)[index] + ((*this)[index] < 0 ? -0.5 : 0.5)); }
    bool asBool(uint32_t index) const { return (*this)[index] != 0.0; }
    uint32_t size() const { return count_; }

private:
    const double* values_;
    uint32_t count_;
};

struct TechniqueDesc {
    const char* id;            // matches the folder name under plugins/
    const char* displayName;
    const char* category;      // "baseline", "hard", "filtered", "soft", "coloured", "reference"
    const char* explanation;   // one paragraph for the classroom panel
    const char* shadowGlsl;    // file in the plugin folder defining vec3 shadowTerm(ShadowInput)
    const ParamDesc* params;
    uint32_t paramCount;
};

// ---------------------------------------------------------------------------------------------
// What the host tells a technique about the frame
enum class LightType : uint32_t { Directional = 0, Spot = 1, Point = 2 };

struct LightInfo {
    LightType type;
    glm::vec3 position;        // spot and point lights
    glm::vec3 direction;       // unit vector the light travels along (directional and spot)
    glm::vec3 color;           // linear RGB, intensity folded in
    float size;                // soft shadows: emitter radius in world units (spot, point) or
                               // angular radius in radians (directional)
    float spotOuterAngle;      // half-angle in radians where a spot light's cone ends
    float spotInnerAngle;      // half-angle in radians where its falloff begins
};

struct CameraInfo {
    glm::mat4 view;
    glm::mat4 projection;
    glm::mat4 viewProjection;
    glm::vec3 position;
    float nearPlane;
    float farPlane;
    glm::ivec2 viewport;       // size of the main render target in pixels
};

struct Bounds {
    glm::vec3 min;
    glm::vec3 max;
};

// Light view and projection fitted by the host around a set of objects.
struct LightSpace {
    glm::mat4 view;
    glm::mat4 projection;
    glm::mat4 viewProjection;
    float nearPlane;
    float farPlane;
    bool perspective;          // spot and point lights; directional lights are orthographic
    glm::vec2 worldSizeAtUnitDepth; // orthographic: extent of the map in world units;
                                    // perspective: extent at distance 1 from the light
};

// Object subsets a technique can draw. Opaque/Translucent refer to the material.
enum class DrawSet : uint32_t { All, Casters, Receivers, OpaqueCasters, TranslucentCasters };

struct ObjectInfo {
    bool castsShadow;
    bool receivesShadow;
    bool translucent;
    bool isPlane;              // flat receiver: plane holds (n, d) with dot(n, x) + d = 0
    glm::vec4 plane;
};

enum class DebugImageKind : uint32_t { Depth, Color, Moments, Mask };
enum class LogLevel : uint32_t { Info, Warning, Error };

struct ProgramDesc {
    const char* vertexFile;    // resolved in the plugin folder, then shaders/
    const char* fragmentFile;  // may be nullptr for depth-only programs
    const char* defines;       // "NAME VALUE;NAME2 VALUE2" or nullptr
};

struct TextureDesc {
    uint32_t target;           // GL_TEXTURE_2D, GL_TEXTURE_2D_ARRAY, GL_TEXTURE_3D, ...
    uint32_t internalFormat;   // sized format, e.g. GL_DEPTH_COMPONENT32F
    int width;
    int height;
    int depth;                 // layers or slices; 1 for 2D
    int levels;                // mip levels, >= 1
    const char* label;         // shown in the memory table and KHR_debug output
};

using GlProc = void (*)();
using GlLoader = GlProc (*)(const char* name);
using ProgramId = uint32_t;    // host handle; stays valid across shader hot reloads

// Host services, one table per loaded technique (so the host can account for its GPU memory and
// release whatever it leaves behind on unload).
class IHost {
public:
    // GL entry points: call gladLoadGL(host.glLoader()) in init(); never keep null pointers.
    virtual GlLoader glLoader() const = 0;
    virtual void log(LogLevel level, const char* message) = 0;

    // Scene and view
    virtual const CameraInfo& camera() const = 0;
    virtual const LightInfo& light() const = 0;
    virtual Bounds sceneBounds(DrawSet set) const = 0;
    virtual LightSpace fitLightSpace(DrawSet set) const = 0;
    // The same fit for another light, e.g. one sample of an area light (ABI 2).
    virtual LightSpace fitLightSpaceFor(const LightInfo& light, DrawSet set) const = 0;
    virtual uint32_t objectCount() const = 0;
    virtual ObjectInfo objectInfo(uint32_t index) const = 0;
    // Draws with `program` bound; the host sets the per-object data (see shaders/common.glsl:
    // uModel and uNormalMatrix from its transform buffer, uBaseColor, uTransmission, uSpecular),
    // drawing objects that share mesh and material as one instanced draw, and the frame UBO.
    virtual void drawScene(DrawSet set, uint32_t glProgram) = 0;
    virtual void drawObject(uint32_t index, uint32_t glProgram) = 0;
    virtual void drawFullscreenTriangle() = 0;

    // Shaders: built from files with #include of shared GLSL in shaders/; rebuilt when a file
    // changes (hot reload). glProgram(id) may therefore change between frames.
    virtual ProgramId buildProgram(const ProgramDesc& desc, std::string& error) = 0;
    virtual uint32_t glProgram(ProgramId id) const = 0;

    // GPU timer scopes around each pass (see GpuPass below)
    virtual void beginGpuPass(const char* name) = 0;
    virtual void endGpuPass() = 0;

    // Tracked GL objects: counted in the technique's memory, released by the host on unload if
    // the technique forgets.
    virtual uint32_t createTexture(const TextureDesc& desc) = 0;
    virtual void destroyTexture(uint32_t texture) = 0;
    virtual uint32_t createBuffer(size_t bytes, const void* data, uint32_t storageFlags, const char* label) = 0;
    virtual void destroyBuffer(uint32_t buffer) = 0;
    virtual uint32_t createFramebuffer(const char* label) = 0;
    virtual void destroyFramebuffer(uint32_t framebuffer) = 0;
    // Completeness check; logs the status with `what` and returns false when incomplete.
    virtual bool checkFramebuffer(uint32_t framebuffer, const char* what) = 0;

    virtual void registerDebugImage(const char* name, uint32_t texture, DebugImageKind kind) = 0;
    // A number the technique measures about itself (e.g. "early-out rate"), shown in the UI and
    // written with benchmark results. Report values read back without stalling (a frame or more late).
    virtual void reportStatistic(const char* name, double value) = 0;

protected:
    ~IHost() = default;
};

class GpuPass {
public:
    GpuPass(IHost& host, const char* name) : host_(host) { host_.beginGpuPass(name); }
    ~GpuPass() { host_.endGpuPass(); }
    GpuPass(const GpuPass&) = delete;
    GpuPass& operator=(const GpuPass&) = delete;

private:
    IHost& host_;
};

// ---------------------------------------------------------------------------------------------
class IShadowTechnique {
public:
    virtual ~IShadowTechnique() = default;
    // Create GL objects; on failure fill `error` and return false (the host skips the plugin).
    virtual bool init(IHost& host, std::string& error) = 0;
    // Passes before the main pass. Reallocate only when a parameter or the viewport changed.
    virtual void renderShadows(const ParamValues& params) = 0;
    // Bind uniforms (locations >= 16) and textures (units >= 4) used by shadowTerm().
    virtual void bindMainPass(uint32_t glProgram, const ParamValues& params) = 0;
    // Release every GL object created in init() or later.
    virtual void shutdown() = 0;
};

struct PluginEntry {
    uint32_t abiVersion;                      // SHADOWLAB_ABI_VERSION the plugin was built with
    const TechniqueDesc* (*describe)();
    IShadowTechnique* (*create)();
    void (*destroy)(IShadowTechnique*);
};

} // namespace shadowlab

#define SHADOWLAB_ENTRY_SYMBOL "shadowlab_plugin_entry"

// Defines the entry point of a plugin: SHADOWLAB_PLUGIN(MyTechnique, kMyDescriptor)
#define SHADOWLAB_PLUGIN(TechniqueType, descriptor)                                                \
    extern "C" __attribute__((visibility("default"))) const shadowlab::PluginEntry*                 \
    shadowlab_plugin_entry() {                                                                     \
        static const shadowlab::PluginEntry entry{                                                 \
            SHADOWLAB_ABI_VERSION, []() -> const shadowlab::TechniqueDesc* { return &(descriptor); }, \
            []() -> shadowlab::IShadowTechnique* { return new TechniqueType(); },                  \
            [](shadowlab::IShadowTechnique* technique) { delete technique; }};                     \
        return &entry;                                                                             \
    }
