// shadowlab plugin API, ABI 3: the whole boundary between the host and a shadow technique.
// docs/plugin-api.md walks through it; the technique kit (shadowlab/kit/) builds on it.
//
// A technique is a shared library under plugins/<id>/ exporting one extern "C" function,
// shadowlab_plugin_entry(), which returns a static PluginEntry. The host reads abiVersion before it
// calls anything else and refuses a mismatch (CLAP's clap_version_is_compatible), then reads the
// static TechniqueDesc (no GL needed: `shadowlab list` never creates a technique), then creates the
// technique and calls init() with a GL context current and a host-services table.
//
// A frame, as the host drives it:
//   host: hot reload, camera and light -> FrameContext, frame uniform block
//   host: camera pre-pass (depth, world position, normal, object id; or depth alone), if the
//         descriptor asks
//   host: default GL state (see "GL state contract" below)
//   technique.renderShadows(frame, params)  shadow maps, filtering passes (in GpuPass scopes)
//   host: default GL state, main program bound
//   technique.bindMainPass(frame, params)   uniforms, textures and samplers for shadowTerm()
//   host: main-pass state, forward Blinn-Phong; `vec3 shadowTerm(ShadowInput s)` (the GLSL file
//         named by TechniqueDesc::shadowGlsl) multiplies the direct light
//
// Threads, GL contexts and lifetimes (the rules every call below follows; CLAP states them per call):
//   - One thread. The host calls into a plugin only from its render thread, the thread that owns
//     the GL context; never from two threads at once. A plugin must not call the host from any
//     other thread (IHost is not thread-safe) and must not keep threads of its own running across
//     calls (hot reload unloads the library right after destroy()).
//   - GL context. describe() is called without any GL context (`shadowlab list`, plugin scans);
//     create() and destroy() may be called without one too, so a constructor or destructor makes
//     no GL call. init(), renderShadows(), bindMainPass(), shutdown(), every installed hook and
//     every IHost method are called with the host's one GL context current.
//   - Lifetimes of what the host hands out:
//       IHost&: from init() until the technique is destroyed;
//       objects(), bounds(): until the next scene load (the host keeps the technique across scene
//         loads: re-read objectCount() and objects() every frame, never cache the pointer);
//       extension(id): the returned struct lives as long as the IHost; what it points at (the
//         camera pre-pass textures, the scene's geometry buffers) is valid during the frame it is
//         queried in (re-query every frame: they change on resize and scene load);
//       ParamValues and its data, FrameContext: during the call they are passed to only;
//       GL names from createTexture/createBuffer/createFramebuffer, ProgramId: until the
//         technique destroys them, or until shutdown() returns (the host releases leftovers);
//         glProgram(id) may change between frames (shader hot reload): look it up every frame.
//   - Lifetimes of what a plugin hands the host: the descriptor, its strings and parameter table
//     while the library is loaded (static data); reported structs (shadow maps, footprints) are
//     copied during the report call; a hook's `user` pointer until it is removed or shutdown().
//
// Versions. SHADOWLAB_ABI_VERSION is the major version: a plugin of another major version is
// refused. SHADOWLAB_ABI_MINOR counts additions that keep every existing layout and meaning (new
// fields at the end of a struct with structSize, new extensions): a host accepts plugins built for
// any minor version of its major version, and reads the newer fields only where structSize (or
// the entry's minor version) says they exist. PluginEntry::abiVersion carries both:
// (minor << 16) | major; ABI 3.0 plugins wrote a bare 3, which reads as 3.0.
//   3.0  the interface below without PluginEntry::structSize;
//   3.1  PluginEntry::structSize; every extension struct initialises its structSize;
//        DrawRequest::primitive (triangles with adjacency); TechniqueDesc::debugViews.
//   3.2  kTechniqueNeedsCameraDepth (a depth-only camera pre-pass); extension
//        "shadowlab.adjacency/1" (the casters' triangles with adjacency in storage buffers).
//
// Growing without breaking plugins: structs that cross the boundary and may grow start with
// structSize (the host reads only what the plugin's size covers, and fills only what the plugin's
// size covers); optional host capabilities are queried by id with IHost::extension() instead of
// new vtable slots. Bump SHADOWLAB_ABI_VERSION only when an existing layout or meaning changes.
//
// GL state contract (set by the host before renderShadows and before bindMainPass):
//   framebuffer 0 bound, viewport = the main target's size (bind your own framebuffer and
//   viewport before drawing);
//   depth test on, GL_LESS, depth writes on; blending off (func ONE/ZERO, equation ADD);
//   face culling off (back faces, CCW front); stencil test off (mask 0xFF, func ALWAYS 0, ops KEEP);
//   scissor test off; clip distances 0-7 off; polygon offset off (0, 0) for fill, line, point;
//   colour writes on for every channel and draw buffer; depth clamp off; sRGB writes off;
//   no sampler object bound on texture units 4-15 (the host's own units 0-3 are the host's);
//   program 0. A technique may change any of it; it need not restore anything.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include <glm/glm.hpp>

#define SHADOWLAB_ABI_VERSION 3u
#define SHADOWLAB_ABI_MINOR 2u
// PluginEntry::abiVersion of a plugin built against this header.
#define SHADOWLAB_ABI_ENTRY_VERSION ((SHADOWLAB_ABI_MINOR << 16) | SHADOWLAB_ABI_VERSION)

namespace shadowlab {

// ---------------------------------------------------------------------------------------------
// Parameters: declared once in the descriptor; the host owns their values (GUI, --set, sweeps,
// tours, hot-reload hand-over) and passes them in. A plugin only reads them.
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

// What a technique asks of the host (TechniqueDesc::flags).
enum TechniqueFlag : uint32_t {
    // The host renders the camera's depth, world position, normal and object id of the opaque
    // surfaces before renderShadows (extension kExtCameraPrepass), once for every technique asking;
    // on the frames its flagConditions allow, when it has any (csm: only for fit = sdsm).
    kTechniqueNeedsCameraPrepass = 1u << 0,
    // ABI 3.2: the camera pre-pass's depth alone (a technique that needs no position, normal or
    // id: shadow volumes). The host then draws depth only, which costs a fraction of the full
    // pass (no RGBA32F, RGBA16F and R32UI writes), and the extension's CameraPrepass has position,
    // normal and objectId 0. The depth is bit for bit the full pass's (the same vertex stage).
    // With both bits, or when another technique of the same view asks for the full pass (a
    // side-by-side comparison), the full pass is drawn once and serves both; this technique still
    // sees only the depth. Hosts before 3.2 ignore the bit (no pre-pass, the extension null), and
    // plugins before 3.2 never set it, so they are unaffected.
    kTechniqueNeedsCameraDepth = 1u << 1,
};

// How a technique means translucent casters to shadow (seed 001): the factor each translucent
// surface of alpha a and transmission colour t contributes, multiplied over every translucent
// surface a shadow ray crosses before the first opaque one (0 from there on). The host judges a
// technique against the reference of its own model as well as the physical one (Physical), so an
// opaque-only technique is not scored for what it never tried to draw (docs/benchmarks.md).
enum class TranslucencyModel : uint32_t {
    Opaque = 0,              // M0: translucent casters block like opaque ones (factor 0)
    Coverage = 1,            // M1: 1 - a, uncoloured (stochastic shadow maps, seed 001 sec. 2.1.2)
    Physical = 2,            // M2: (1 - a) + a t, coloured (CSSM, seed 001 sec. 2.1.3: p = a (1 - t))
    ModifiedTranslucent = 3, // M3: (1 - a) t (seed 001 sec. 4.2.1, "modified" translucent shadows)
    Ignore = 4,              // translucent casters cast nothing (factor 1): a map of OpaqueCasters only
};
constexpr uint32_t kTranslucencyModelCount = 5;

// A flag that holds only for some values of one parameter (TechniqueDesc::flagConditions): its
// bits apply while parameter `param` has one of `values` ("sdsm", "a|b": Enum labels or numbers,
// as --set takes them) and are dropped otherwise. The host evaluates the conditions with the
// current values every frame, so a parameter change takes effect on the frame it is made; a flag
// named by no condition holds always. E.g. csm: the camera pre-pass only while fit = sdsm.
struct FlagCondition {
    uint32_t flags = 0;                // TechniqueFlag bits (a subset of TechniqueDesc::flags)
    const char* param = nullptr;       // a parameter id of this descriptor
    const char* values = nullptr;      // "label|label|number"
};

struct TechniqueDesc {
    uint32_t structSize = sizeof(TechniqueDesc);
    const char* id = nullptr;          // matches the folder name under plugins/
    const char* displayName = nullptr;
    const char* category = nullptr;    // "baseline", "hard", "filtered", "soft", "coloured", "reference"
    const char* explanation = nullptr; // one paragraph for the classroom panel
    const char* shadowGlsl = nullptr;  // file in the plugin folder defining vec3 shadowTerm(ShadowInput)
    const ParamDesc* params = nullptr;
    uint32_t paramCount = 0;
    uint32_t flags = 0;                // TechniqueFlag bits
    // Added in ABI 3 after flags: read only when structSize covers it (older plugins: Opaque).
    TranslucencyModel translucencyModel = TranslucencyModel::Opaque;
    // Added in ABI 3 after translucencyModel, read only when structSize covers them (older
    // plugins: none, their flags hold always). `flags` stays what the technique may ask for.
    const FlagCondition* flagConditions = nullptr;
    uint32_t flagConditionCount = 0;
    // Added in ABI 3.1 after flagConditionCount, read only when structSize covers it (older
    // plugins: unknown, the host lists what the technique reports). The host debug views that
    // apply to this technique, '|'-separated, from "footprint|texel-grid|coverage|focus-body|kernel"
    // (the ones its reports feed); its own debug images are listed by name as it reports them.
    // Empty: none of them. The panel and `shadowlab list` show it; explanations need not repeat it.
    const char* debugViews = nullptr;
};

// ---------------------------------------------------------------------------------------------
// What the host tells a technique about the frame
enum class LightType : uint32_t { Directional = 0, Spot = 1, Point = 2 };

struct LightInfo {
    LightType type = LightType::Directional;
    glm::vec3 position{0.0f, 10.0f, 0.0f};   // spot and point lights
    glm::vec3 direction{0.0f, -1.0f, 0.0f};  // unit vector the light travels along (directional, spot)
    glm::vec3 color{1.0f};                   // linear RGB, intensity folded in
    float size = 0.0f;                       // soft shadows: emitter radius in world units (spot,
                                             // point) or angular radius in radians (directional)
    float spotOuterAngle = 0.5f;             // half-angle in radians where a spot light's cone ends
    float spotInnerAngle = 0.4f;             // half-angle in radians where its falloff begins
};

struct CameraInfo {
    glm::mat4 view{1.0f};
    glm::mat4 projection{1.0f};
    glm::mat4 viewProjection{1.0f};
    glm::mat4 inverseViewProjection{1.0f};
    glm::vec3 position{0.0f};
    float nearPlane = 0.1f;
    float farPlane = 100.0f;
    float fovY = 0.785f;                     // radians, vertical
    float aspect = 1.0f;                     // width / height
    glm::ivec2 viewport{1};                  // size of the main render target in pixels
    // World-space corners of the view frustum: index bit 0 = +x, bit 1 = +y, bit 2 = far plane
    // (the same order as a box's corners, see kit/focus.h).
    glm::vec3 frustumCorners[8]{};
};

// Passed to every per-frame call. Read fields only up to structSize (kit::frameHas()).
struct FrameContext {
    uint32_t structSize = sizeof(FrameContext);
    uint32_t version = 1;                    // layout version of this struct
    uint64_t frameIndex = 0;                 // counts rendered frames from 0
    uint32_t randomSeed = 0;                 // differs every frame (a hash of frameIndex): stochastic techniques
    float time = 0.0f;                       // seconds: wall clock in the window, 1/60 s a frame headless
    float deltaTime = 0.0f;
    CameraInfo camera;
    glm::mat4 previousViewProjection{1.0f}; // the camera's on the previous frame (this frame's on the first)
    LightInfo light;
};

struct Bounds {
    glm::vec3 min{0.0f};
    glm::vec3 max{0.0f};
};

// Light view and projection fitted by the host.
struct LightSpace {
    glm::mat4 view{1.0f};
    glm::mat4 projection{1.0f};
    glm::mat4 viewProjection{1.0f};
    float nearPlane = 0.0f;
    float farPlane = 1.0f;
    bool perspective = false;                // spot and point lights; directional lights are orthographic
    glm::vec2 worldSizeAtUnitDepth{1.0f};    // orthographic: extent of the map in world units;
                                             // perspective: extent at distance 1 from the light
};

// Object subsets a technique can draw. Opaque/Translucent refer to the material.
enum class DrawSet : uint32_t { All, Casters, Receivers, OpaqueCasters, TranslucentCasters, Opaque, Translucent };

enum ObjectFlag : uint32_t {
    kObjectCastsShadow = 1u << 0,
    kObjectReceivesShadow = 1u << 1,
    kObjectTranslucent = 1u << 2,            // material alpha < 1
    kObjectPlane = 1u << 3,                  // flat receiver: plane holds (n, d), dot(n, x) + d = 0
};

// Computed once per scene load.
struct ObjectInfo {
    Bounds bounds;                           // world space, axis aligned
    glm::vec3 center{0.0f};                  // of the bounds
    uint32_t flags = 0;                      // ObjectFlag bits
    glm::vec3 baseColor{0.8f};               // linear RGB
    float alpha = 1.0f;                      // coverage
    glm::vec3 transmission{0.0f};            // colour of light passing through
    uint32_t material = 0;                   // index; objects sharing one share all of the above
    glm::vec4 plane{0.0f, 1.0f, 0.0f, 0.0f};
    bool castsShadow() const { return flags & kObjectCastsShadow; }
    bool receivesShadow() const { return flags & kObjectReceivesShadow; }
    bool translucent() const { return flags & kObjectTranslucent; }
    bool isPlane() const { return flags & kObjectPlane; }
};

enum class DrawOrder : uint32_t { Scene, FrontToBack, BackToFront };

// What a draw hands the vertex stages (DrawRequest::primitive, ABI 3.1).
enum class DrawPrimitive : uint32_t {
    Triangles = 0,
    // GL_TRIANGLES_ADJACENCY, 6 vertices a triangle (a, n_ab, b, n_bc, c, n_ca): n_xy is the corner
    // opposite edge xy in the mesh's one other triangle that has the edge the other way round
    // (vertices welded by position). Where there is no such neighbour (an open boundary, an edge of
    // three or more triangles, a neighbour wound the other way) n_xy is the triangle's own
    // opposite corner (n_ab = c). The host also sets `layout(location = 6) uniform int`
    // (uClosedMesh) to 1 for meshes in which every edge has its neighbour. Built once per scene
    // load, on the first such draw (render/mesh_adjacency.h). For shadow volumes' silhouettes.
    TrianglesAdjacency = 1,
};

// One drawScene() call. Objects that share mesh and material are drawn as one instanced draw
// where order and culling allow.
struct DrawRequest {
    uint32_t structSize = sizeof(DrawRequest);
    DrawSet set = DrawSet::All;
    // Sorting by the objects' bounds centres: distance from a point (orderReference.w = 1) or
    // along a direction (w = 0), e.g. front to back from the light.
    DrawOrder order = DrawOrder::Scene;
    glm::vec4 orderReference{0.0f};
    // Culling: an object is drawn only if its bounds reach the positive side of every plane
    // (dot(plane.xyz, p) + plane.w >= 0 for some corner p): a frustum or a focus body.
    const glm::vec4* cullPlanes = nullptr;
    uint32_t cullPlaneCount = 0;
    // Added in ABI 3.1, read only when structSize covers it (older plugins: triangles).
    DrawPrimitive primitive = DrawPrimitive::Triangles;
};

enum class DebugImageKind : uint32_t { Depth, Color, Moments, Mask };
enum class LogLevel : uint32_t { Info, Warning, Error };

// Files resolve in the plugin folder, then shaders/, then app/include (the kit's shared headers).
// Either compute alone, or vertex (+ geometry) (+ fragment: none for depth-only programs).
struct ProgramDesc {
    const char* vertexFile = nullptr;
    const char* geometryFile = nullptr;
    const char* fragmentFile = nullptr;
    const char* computeFile = nullptr;
    const char* defines = nullptr;           // "NAME VALUE;NAME2 VALUE2"
};

struct TextureDesc {
    uint32_t target = 0x0DE1;                // GL_TEXTURE_2D; also 2D arrays, 3D, cube maps, cube-map
                                             // arrays, 2D multisample (arrays), 1D
    uint32_t internalFormat = 0;             // sized format, e.g. GL_DEPTH_COMPONENT32F
    int width = 1;
    int height = 1;
    int depth = 1;                           // layers (arrays), slices (3D), cubes (cube-map arrays)
    int levels = 1;                          // mip levels, >= 1
    int samples = 0;                         // multisample targets only
    const char* label = nullptr;             // shown in the memory table and KHR_debug output
};

// Host-owned sampler objects (clamp to edge); bind with glBindSampler(unit, host.sampler(kind)).
// Compare kinds compare with GL_LEQUAL (sampler2DShadow: 1 where ref <= stored depth).
enum class SamplerKind : uint32_t { Nearest, Linear, LinearMipmap, CompareNearest, CompareLinear, NearestMipmap };

using GlProc = void (*)();
using GlLoader = GlProc (*)(const char* name);
using ProgramId = uint32_t;                  // host handle; stays valid across shader hot reloads

// Extension "shadowlab.camera-prepass/1": the host's camera pre-pass of this frame, for
// techniques whose descriptor has kTechniqueNeedsCameraPrepass or kTechniqueNeedsCameraDepth and
// whose flagConditions allow it this frame (null otherwise: no pre-pass was rendered for it). With
// kTechniqueNeedsCameraDepth alone only `depth` is set (position, normal and objectId are 0).
// Textures are host-owned and read-only for techniques: sample them, or attach `depth` to a
// framebuffer with depth writes off. Same size as the main target, single-sample, opaque objects
// only, the same vertex transform as the main pass (so depths match it exactly).
// The stencil of `depth` is the exception: it is the technique's from renderShadows to the end of
// its main pass. The host clears it to 0 with the depth and never reads or writes it otherwise,
// so a technique may count into it (attach `depth`, depth writes off, stencil writes on) and read
// the count in shadowTerm() through `stencil`, without a depth copy of its own (shadow volumes).
// Techniques drawn side by side share one pre-pass: clear the stencil before counting.
// Attach `depth` again each frame: the host reallocates its targets (resize, a fuller kind), and
// a recycled GL name cannot be told from the old one.
#define SHADOWLAB_EXT_CAMERA_PREPASS "shadowlab.camera-prepass/1"
struct CameraPrepass {
    uint32_t structSize = sizeof(CameraPrepass);
    uint32_t depth;                          // GL_DEPTH24_STENCIL8
    uint32_t position;                       // GL_RGBA32F: xyz world, w = 1 where geometry was drawn (0: depth only)
    uint32_t normal;                         // GL_RGBA16F: xyz unit world normal facing the viewer (0: depth only)
    uint32_t objectId;                       // GL_R32UI: object index + 1, 0 = background (0: depth only)
    glm::ivec2 size;
    // Added in ABI 3 after size, read only when structSize covers it: a texture view of `depth`
    // that samples its stencil (GL_DEPTH_STENCIL_TEXTURE_MODE = GL_STENCIL_INDEX; a usampler2D
    // with a nearest sampler), so that `depth` itself keeps sampling as depth for everyone else.
    uint32_t stencil = 0;
};

// Extension "shadowlab.shadow-maps/1": the shadow maps shadowTerm() reads this frame, told to the
// host once a frame after renderShadows (each call replaces the last list). The host measures
// the texel footprint m from them (eval, the footprint view) and draws the light frustum, texel
// grid and cascade colours in its debug views. A technique that never reports is measured
// without m. Maps are listed in the order a pixel picks them: the first whose view-distance
// range holds the pixel and whose clip volume holds the point serves it (cascades, cube faces).
#define SHADOWLAB_EXT_SHADOW_MAPS "shadowlab.shadow-maps/1"
struct ShadowMapInfo {
    uint32_t structSize = sizeof(ShadowMapInfo);
    glm::mat4 worldToClip{1.0f};             // world -> the map's clip space: xy/w in [-1, 1] spans
                                             // the map, z/w in [-1, 1] its depth range
    glm::ivec2 size{0};                      // texels of the level shadowTerm() reads
    float viewDistanceBegin = 0.0f;          // camera view depths this map serves (cascade splits);
    float viewDistanceEnd = 1e30f;           // a single map serves them all
    uint32_t layer = 0;                      // array layer or cube face, for labels
    const char* label = nullptr;             // "cascade 2", "+x face"; may be null
    // Added in ABI 3 after label, read only when structSize covers them (older plugins: none).
    // The focus body B the map was fitted around (seed 002 eq. 4.2, kit/focus.h), as world-space
    // edges: 2 * focusBodyEdgeCount points, edge i from [2i] to [2i + 1]. Valid during the report
    // call only (the host copies them). The host's `focus-body` view draws them.
    const glm::vec3* focusBodyEdges = nullptr;
    uint32_t focusBodyEdgeCount = 0;
};
struct ShadowMapReport {
    uint32_t structSize = sizeof(ShadowMapReport);
    void* context;
    void (*report)(void* context, const ShadowMapInfo* maps, uint32_t count);
};

// Extension "shadowlab.filter-footprint/1": what shadowTerm() filters over around a point of the
// first reported map, told once a frame after renderShadows (each call replaces the last; cleared
// before every renderShadows), so the host can show the kernel's footprint around a pixel (the
// `kernel` view, `--probe`): it re-evaluates the taps on the CPU from the raw depths of
// `depthTexture`. Data only: the host owns the measurement and the drawing.
#define SHADOWLAB_EXT_FILTER_FOOTPRINT "shadowlab.filter-footprint/1"
enum class FilterKernel : uint32_t {
    None = 0,
    Box = 1,    // n x n taps `spacing` texels apart around the point (pcf)
    Disc = 2,   // n x n jittered disc samples of radius `spacing` texels, outer ring first, early out (adaptive-pcf)
    Pcss = 3,   // blocker search over n_s x n_s disc samples, penumbra estimate, then Disc with that radius (pcss)
};
struct FilterFootprint {
    uint32_t structSize = sizeof(FilterFootprint);
    FilterKernel kernel = FilterKernel::None;
    int32_t taps = 1;                // n: Box n x n taps; Disc n x n samples; Pcss the filter's n_f
    float spacing = 1.0f;            // Box: texels between taps; Disc: the radius in texels
    uint32_t bilinear = 0;           // 1: each tap is a 2x2 bilinear comparison
    int32_t sets = 1;                // Disc, Pcss: m x m disc sets, set = pixel mod m
    uint32_t discSeed = 1;           // the filter's disc sets (jittered_disk::makeOffsetTexture's seed)
    int32_t searchTaps = 0;          // Pcss: n_s
    uint32_t searchSeed = 2;         // Pcss: the search's disc sets
    uint32_t searchBound = 0;        // Pcss: 0 near plane (eq. 3.18), 1 min-depth, 2 depth-range
    float lightSize = 0.0f;          // Pcss: world radius (perspective map) or tan(angular radius)
    float coneBias = 0.0f;           // multiplier of the receiver slope; 0 off
    uint32_t coherent = 0;           // Disc: the early out is decided per 2x2 quad
    uint32_t depthTexture = 0;       // GL name of the map's raw depths (2D, level 0); 0: none
    glm::vec4 lightDepth{0.0f};      // near, far, 1 perspective / 0 orthographic, resolution
    glm::vec4 lightWorldSize{0.0f};  // xy: map extent in world units (orthographic) or at unit depth
    glm::vec4 lightAxis{0.0f};       // xyz: world direction along which the map measures depth
};
struct FilterFootprintReport {
    uint32_t structSize = sizeof(FilterFootprintReport);
    void* context;
    void (*report)(void* context, const FilterFootprint* footprint);
};

// Extension "shadowlab.translucent-draws/1": for a technique whose maps must change between the
// host's translucent draws (seed 001's composited translucent shadows, sec. 4.2.3, rebuild the
// nearest translucent depth and the shadow colour from the meshes nearer the light than each
// mesh drawn). The technique installs a hook (in init(); a null hook removes it). While one is
// installed, every pass of the host that draws translucent receivers with the technique's
// shadowTerm() (the main pass, and the evaluation's translucent layers) draws them one at a
// time, back to front from the camera by their bounds' centres, as it always does, and:
//   before each object: beforeObject(user, frame, params, objectIndex). The hook may draw
//     anything into its own framebuffers; then the host sets the GL state contract, binds the
//     main program, calls bindMainPass(frame, params) again, sets its main-pass state and draws
//     the object;
//   after the last one: beforeObject(user, frame, params, kTranslucentDrawsDone), so that the
//     next bindMainPass binds what the opaque receivers read again (the host calls it next).
// GpuPass scopes inside the hook are not timed on their own: the host times all the translucent
// draws with their hooks as one scope, "translucent draws", inside "main" (seed 001 sec. 5.3.1
// times composited shadows the same way, one scope around the translucent loop).
#define SHADOWLAB_EXT_TRANSLUCENT_DRAWS "shadowlab.translucent-draws/1"
constexpr uint32_t kTranslucentDrawsDone = 0xFFFFFFFFu;
struct TranslucentDrawHook {
    uint32_t structSize = sizeof(TranslucentDrawHook);
    void* user = nullptr;
    void (*beforeObject)(void* user, const FrameContext& frame, const ParamValues& params, uint32_t objectIndex) = nullptr;
};
struct TranslucentDraws {
    uint32_t structSize = sizeof(TranslucentDraws);
    void* context;
    void (*install)(void* context, const TranslucentDrawHook* hook);   // copied; null removes the hook
};

// Extension "shadowlab.ray-tracing/1": the scene's shadow casters as a BVH in storage buffers, for
// techniques that trace shadow rays on the GPU (issue 27; shaders/ray_trace.glsl traverses it:
// #include "ray_trace.glsl" and bind the five buffers on its RT_*_BINDING points). scene() builds
// the BVH on its first call after a scene load (binned SAH on the CPU, app/src/render/bvh.h, which
// documents the layouts; seconds for millions of triangles) and returns the same struct until the
// next scene load, which releases the buffers: call scene() every frame, never keep the names.
// The buffers are host-owned and read-only for techniques (GL_SHADER_STORAGE_BUFFER, std430);
// every caster is in world space (each object's transform applied to its mesh); objects that cast
// no shadow are left out. Call scene() only from the render thread with the host's GL context
// current (renderShadows, bindMainPass, hooks). Their memory is the host's (`bytes`), not counted
// in the technique's; report it as a statistic if the bench should show it. Never null on a host
// that has the extension; an empty scene gives one empty leaf.
#define SHADOWLAB_EXT_RAY_TRACING "shadowlab.ray-tracing/1"
struct RayTracingScene {
    uint32_t structSize = sizeof(RayTracingScene);
    uint32_t nodes = 0;              // GL buffer: 32-byte nodes (lo.xyz, first; hi.xyz, count), root first
    uint32_t triangles = 0;          // GL buffer: 48-byte world-space triangles in leaf order
    uint32_t uvs = 0;                // GL buffer: 32-byte uv records of textured triangles
    uint32_t materials = 0;          // GL buffer: 32-byte records ((t, alpha), (flags, first texel, w, h))
    uint32_t texels = 0;             // GL buffer: transmission textures, RGBA8 in one uint per texel
    uint32_t nodeCount = 0;
    uint32_t triangleCount = 0;      // shadow-casting triangles (0 for an empty scene)
    uint32_t materialCount = 0;
    uint32_t depth = 0;              // longest root-to-leaf path (ray_trace.glsl's stack holds 64)
    float rayOffset = 1e-4f;         // the Embree reference's shadow-ray offset (world units)
    float buildMilliseconds = 0.0f;  // CPU build time, upload excluded
    uint64_t bytes = 0;              // the five buffers together
};
struct RayTracing {
    uint32_t structSize = sizeof(RayTracing);
    void* context;
    const RayTracingScene* (*scene)(void* context);
};

// Extension "shadowlab.adjacency/1" (ABI 3.2): the shadow casters' triangles with adjacency in
// storage buffers, for techniques that find silhouette edges in a compute pass (shadow volumes'
// extract = compute). The same data DrawPrimitive::TrianglesAdjacency draws (render/mesh_adjacency.h:
// vertices welded by position, the rules for open, non-manifold and inconsistently wound edges),
// built once per scene load by the first scene() call or adjacency draw, released by the next
// scene load: call scene() every frame, never keep the names or the pointer. Host-owned,
// read-only buffers (GL_SHADER_STORAGE_BUFFER, std430):
//   vertices:   every mesh's vertices, 8 floats each (position xyz, normal xyz, uv);
//   indices:    6 uints a triangle (a, n_ab, b, n_bc, c, n_ca), relative to the batch's
//               baseVertex; n_xy is the triangle's own opposite corner where the edge has no
//               neighbour;
//   transforms: the objects' transforms (common.glsl's ObjectTransforms: model, normal matrix),
//               which the host also keeps on storage binding 0.
// `batches`: the objects that cast shadows (DrawSet::Casters) as runs of consecutive objects
// sharing a mesh, in scene order: objects firstObject .. firstObject + objectCount - 1, each with
// the mesh's triangleCount triangles from indices[6 * firstTriangle]; `closed` is 1 where every
// edge of the mesh has its neighbour (uClosedMesh). Call scene() only from the render thread with
// the host's GL context current. The memory is the host's (not in the technique's GPU bytes).
#define SHADOWLAB_EXT_ADJACENCY "shadowlab.adjacency/1"
struct AdjacencyBatch {
    uint32_t firstObject = 0;
    uint32_t objectCount = 0;
    uint32_t firstTriangle = 0;
    uint32_t triangleCount = 0;
    int32_t baseVertex = 0;
    uint32_t closed = 0;
};
struct AdjacencyScene {
    uint32_t structSize = sizeof(AdjacencyScene);
    uint32_t vertices = 0;                   // GL buffer
    uint32_t indices = 0;                    // GL buffer
    uint32_t transforms = 0;                 // GL buffer
    const AdjacencyBatch* batches = nullptr;
    uint32_t batchCount = 0;
    uint64_t triangles = 0;                  // sum of objectCount * triangleCount over the batches
    uint64_t closedTriangles = 0;            // of those, in closed meshes
};
struct Adjacency {
    uint32_t structSize = sizeof(Adjacency);
    void* context;
    const AdjacencyScene* (*scene)(void* context);
};

// Host services, one table per loaded technique (so the host can account for its GPU memory and
// release whatever it leaves behind on unload).
class IHost {
public:
    // GL entry points: call gladLoadGL(host.glLoader()) in init() (kit::TechniqueBase does).
    virtual GlLoader glLoader() const = 0;
    virtual void log(LogLevel level, const char* message) = 0;
    // An optional capability by id (SHADOWLAB_EXT_...), or nullptr when the host lacks it.
    virtual const void* extension(const char* id) const = 0;

    // Scene: computed once per scene load.
    virtual uint32_t objectCount() const = 0;
    virtual const ObjectInfo* objects() const = 0;
    virtual Bounds bounds(DrawSet set) const = 0;

    // Fitting a light space. Directional lights get an orthographic map, spot and point lights a
    // perspective one (a single frustum). Depth always reaches towards the light far enough to
    // hold every caster in front of the fitted region, so casters outside it still cast into it.
    virtual LightSpace fitLightSpace(const LightInfo& light, const Bounds& bounds) const = 0;
    virtual LightSpace fitLightSpaceToPoints(const LightInfo& light, const glm::vec3* points, uint32_t count) const = 0;
    // The camera frustum between view distances near and far (seed 000 eq. 3.9-3.10; cascades).
    virtual LightSpace fitLightSpaceToFrustumSlice(const LightInfo& light, const CameraInfo& camera, float nearDistance,
                                                   float farDistance) const = 0;
    LightSpace fitLightSpace(const LightInfo& light, DrawSet set) const { return fitLightSpace(light, bounds(set)); }

    // Draws with `glProgram` bound; the host sets the per-object data (shaders/common.glsl: uModel
    // and uNormalMatrix from its transform buffer, uBaseColor, uTransmission, uSpecular).
    virtual void drawScene(const DrawRequest& request, uint32_t glProgram) = 0;
    virtual void drawObject(uint32_t index, uint32_t glProgram) = 0;
    virtual void drawFullscreenTriangle() = 0;
    void drawScene(DrawSet set, uint32_t glProgram) {
        DrawRequest request;
        request.set = set;
        drawScene(request, glProgram);
    }

    // Shaders: built from files with #include; rebuilt when a file changes (hot reload), so
    // glProgram(id) may change between frames.
    virtual ProgramId buildProgram(const ProgramDesc& desc, std::string& error) = 0;
    virtual uint32_t glProgram(ProgramId id) const = 0;
    virtual void destroyProgram(ProgramId id) = 0;

    // GPU timer scopes around each pass (see GpuPass below)
    virtual void beginGpuPass(const char* name) = 0;
    virtual void endGpuPass() = 0;

    // Tracked GL objects: counted exactly in the technique's memory (every mip, layer, cube face
    // and sample), released by the host on unload if the technique forgets.
    virtual uint32_t createTexture(const TextureDesc& desc) = 0;
    virtual void destroyTexture(uint32_t texture) = 0;
    virtual uint32_t createBuffer(size_t bytes, const void* data, uint32_t storageFlags, const char* label) = 0;
    virtual void destroyBuffer(uint32_t buffer) = 0;
    virtual uint32_t createFramebuffer(const char* label) = 0;
    virtual void destroyFramebuffer(uint32_t framebuffer) = 0;
    // Completeness check; logs the status with `what` and returns false when incomplete.
    virtual bool checkFramebuffer(uint32_t framebuffer, const char* what) = 0;
    virtual uint32_t sampler(SamplerKind kind) const = 0;

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
// Every method has a default, so a technique overrides only what it uses.
class IShadowTechnique {
public:
    virtual ~IShadowTechnique() = default;
    // Create GL objects; on failure fill `error` and return false (the host skips the plugin).
    virtual bool init(IHost& host, std::string& error) {
        (void)host;
        (void)error;
        return true;
    }
    // Passes before the main pass. Reallocate only when a parameter or the viewport changed.
    virtual void renderShadows(const FrameContext& frame, const ParamValues& params) {
        (void)frame;
        (void)params;
    }
    // With the main program bound: uniforms (blocks at binding 1+, locations 16+), textures and
    // samplers (units 4+) used by shadowTerm(). Pipeline state set here is overridden by the host.
    virtual void bindMainPass(const FrameContext& frame, const ParamValues& params) {
        (void)frame;
        (void)params;
    }
    // Release GL objects not held by kit handles; the host destroys the technique right after.
    virtual void shutdown() {}
};

// What shadowlab_plugin_entry() returns: static data, valid while the library is loaded.
struct PluginEntry {
    uint32_t abiVersion;                      // SHADOWLAB_ABI_ENTRY_VERSION: (minor << 16) | major
    const TechniqueDesc* (*describe)();       // no GL context needed; the same pointer every call
    IShadowTechnique* (*create)();            // no GL call in the constructor (see above)
    void (*destroy)(IShadowTechnique*);       // after shutdown(); no GL call in the destructor
    // Added in ABI 3.1, read only when abiVersion's minor version is 1 or more (3.0 plugins end
    // before it). Later minor versions append fields after it; the host reads what it covers.
    uint32_t structSize = sizeof(PluginEntry);
};

} // namespace shadowlab

#define SHADOWLAB_ENTRY_SYMBOL "shadowlab_plugin_entry"

// Defines the entry point of a plugin: SHADOWLAB_PLUGIN(MyTechnique, kMyDescriptor)
#define SHADOWLAB_PLUGIN(TechniqueType, descriptor)                                                \
    extern "C" __attribute__((visibility("default"))) const shadowlab::PluginEntry*                 \
    shadowlab_plugin_entry() {                                                                     \
        static const shadowlab::PluginEntry entry{                                                 \
            SHADOWLAB_ABI_ENTRY_VERSION, []() -> const shadowlab::TechniqueDesc* { return &(descriptor); }, \
            []() -> shadowlab::IShadowTechnique* { return new TechniqueType(); },                  \
            [](shadowlab::IShadowTechnique* technique) { delete technique; },                      \
            sizeof(shadowlab::PluginEntry)};                                                       \
        return &entry;                                                                             \
    }
