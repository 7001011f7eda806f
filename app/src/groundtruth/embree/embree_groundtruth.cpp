// Ray-traced ground truth with Intel Embree 3 on the CPU (the module libshadowlab_groundtruth.so;
// interface and semantics in app/src/groundtruth/groundtruth.h).
//
// - One BVH per scene, built once in setScene() and reused for every frame and technique. A mesh
//   used by one object is flattened into world space; a mesh shared by several objects (forests
//   of instanced trees) is built once in object space and referenced by instance geometries.
//   Ray masks separate what primary rays see (every object) from what blocks shadow rays
//   (castsShadow objects).
// - Shadow rays start at p + n * rayOffset(), n the G-buffer normal turned towards the light,
//   rayOffset() = 1e-4 * the scene's size: far above float error in positions read back from a
//   G-buffer (about 1e-7 relative), far below a pixel's footprint, so the reference has no acne
//   and no visible leak at contacts.
// - Soft shadows: a jittered sqrt(N) x sqrt(N) grid per pixel mapped to the emitter with
//   Shirley and Chiu's concentric map; the jitter of each stratum is a hash of (pixel, seed,
//   stratum), so the image does not depend on the thread count, and the adaptive reference (a
//   first batch of the strata everywhere, all N only where needed: traceSoft) gives a refined
//   pixel exactly the uniform reference's value. Per pixel, the reference also estimates its own
//   sampling error (standardError), the floor under any soft metric measured against it.
// - Translucency models (ReferenceOptions::model): with Opaque every caster blocks (one occlusion
//   query per ray). Otherwise hits are walked in order along the ray; a translucent caster of
//   alpha a and transmission colour t lets through crossingFactor(model, a, t) per channel
//   (groundtruth.h: Physical (1 - a) + a t, a fraction 1 - a of the light misses its coverage and
//   the rest is filtered by t; Coverage 1 - a; ModifiedTranslucent (1 - a) t; Ignore 1); the
//   first opaque caster gives 0. Every surface crossing counts, so a closed translucent solid
//   filters twice (entry and exit), as a rasteriser accumulating all translucent fragments does.
// - Rows are shared between std::threads through an atomic counter; rays of a row (hard) or of
//   a pixel (soft) go to Embree as one stream, which it traces as packets.
#include <embree3/rtcore.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <exception>
#include <limits>
#include <memory>
#include <mutex>
#include <numbers>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include <glm/glm.hpp>

#include "groundtruth/groundtruth.h"

namespace shadowlab {
namespace {

constexpr unsigned kMaskVisible = 1u; // primary rays: every object
constexpr unsigned kMaskCaster = 2u;  // shadow rays: objects with castsShadow
constexpr float kInfinity = std::numeric_limits<float>::infinity();
constexpr int kMaxTransmissionHits = 256; // guard against degenerate stacks of coplanar quads

// ---------------------------------------------------------------------------------------------
// Sampling

// SplitMix64 (Steele, Lea and Flood 2014, "Fast splittable pseudorandom number generators"):
// its finaliser turns consecutive counters into independent-looking 64-bit values.
uint64_t mix64(uint64_t z) {
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}
constexpr uint64_t kGolden = 0x9e3779b97f4a7c15ull;

// Counter-based random numbers of one pixel: element k of a stream is a hash of (pixel, seed,
// stream, k), so a sample does not depend on which samples were drawn before it (the adaptive
// reference's first batch and a refined pixel's full pattern see the same jitter), nor on the
// thread that traces the pixel.
class PixelRandom {
public:
    PixelRandom(uint64_t pixel, uint32_t seed)
        : key_(mix64((static_cast<uint64_t>(seed) << 32 | (pixel & 0xffffffffu)) + kGolden)) {}
    enum Stream : uint64_t { kJitter = 0, kChoice = 1 };
    uint64_t bits(Stream stream, uint64_t k) const { return mix64(key_ + (2 * k + stream + 1) * kGolden); }
    // Two floats in [0, 1) from one element (24 bits each).
    glm::vec2 pair(Stream stream, uint64_t k) const {
        const uint64_t b = bits(stream, k);
        return {static_cast<float>(b >> 40) * 0x1p-24f, static_cast<float>((b >> 16) & 0xffffffu) * 0x1p-24f};
    }

private:
    uint64_t key_;
};

// Shirley and Chiu 1997, "A low distortion map between disk and square": concentric squares to
// concentric circles, so the strata stay compact on the disc.
glm::vec2 concentricDisc(glm::vec2 u) {
    const glm::vec2 o = 2.0f * u - 1.0f;
    if (o.x == 0.0f && o.y == 0.0f) return glm::vec2(0.0f);
    constexpr float quarterPi = std::numbers::pi_v<float> / 4.0f;
    float r, phi;
    if (std::abs(o.x) > std::abs(o.y)) {
        r = o.x;
        phi = quarterPi * (o.y / o.x);
    } else {
        r = o.y;
        phi = 2.0f * quarterPi - quarterPi * (o.x / o.y);
    }
    return r * glm::vec2(std::cos(phi), std::sin(phi));
}

// Duff et al. 2017, "Building an orthonormal basis, revisited": branchless, no singularity but
// the sign switch at n.z = 0.
void orthonormalBasis(glm::vec3 n, glm::vec3& t, glm::vec3& b) {
    const float sign = std::copysign(1.0f, n.z);
    const float a = -1.0f / (sign + n.z);
    const float c = n.x * n.y * a;
    t = glm::vec3(1.0f + sign * n.x * n.x * a, sign * c, -sign * n.x);
    b = glm::vec3(c, sign + n.y * n.y * a, -n.y);
}

// Jittered stratification of N samples: an nx * ny grid (nx = floor(sqrt N)), the N - nx*ny
// left over drawn uniformly. Each sample is uniform over its stratum or the square, so the mean
// stays unbiased for any N. Stratum k is cell (k % nx, k / nx); through the concentric map the
// cells of the grid's border (k on the square's boundary) lie on the emitter's rim, in angular
// order along the border.
struct Strata {
    explicit Strata(int n) : count(std::max(1, n)) {
        nx = std::max(1, static_cast<int>(std::sqrt(static_cast<double>(count))));
        ny = count / nx;
    }
    glm::vec2 sample(int k, const PixelRandom& random) const {
        const glm::vec2 j = random.pair(PixelRandom::kJitter, static_cast<uint64_t>(k));
        if (k >= nx * ny) return j;
        return {(static_cast<float>(k % nx) + j.x) / static_cast<float>(nx),
                (static_cast<float>(k / nx) + j.y) / static_cast<float>(ny)};
    }
    int grid() const { return nx * ny; }
    int borderCells() const { return nx < 2 || ny < 2 ? grid() : 2 * (nx + ny) - 4; }
    // The t-th cell of the border, counter-clockwise from the corner (0, 0).
    int borderCell(int t) const {
        if (t < nx) return t;                                               // bottom row
        if ((t -= nx) < ny - 1) return (t + 1) * nx + nx - 1;               // right column, upwards
        if ((t -= ny - 1) < nx - 1) return (ny - 1) * nx + (nx - 2 - t);    // top row, leftwards
        t -= nx - 1;
        return (ny - 2 - t) * nx;                                           // left column, downwards
    }
    int count, nx, ny;
};

// The first batch of the adaptive reference: `size` distinct strata of the N-sample pattern,
// chosen per pixel (PixelRandom::kChoice). Half of them (at most the border's cells) are border
// cells at even spacing along the border from a random start: rays to the emitter's rim, at most
// 360 / (size / 2) degrees apart. The rest is one random cell from each of about size / 2 blocks
// of a coarse grid over the square: rays spread over the whole emitter. The batch only decides
// whether a pixel stops; a pixel that goes on traces all N strata, so how the batch is chosen
// never biases a value.
void chooseFirstBatch(const Strata& strata, int size, const PixelRandom& random, std::vector<int>& batch,
                      std::vector<uint8_t>& used) {
    batch.clear();
    const int border = strata.borderCells();
    const int rim = std::min(size / 2, border);
    if (rim > 0) {
        const double spacing = static_cast<double>(border) / static_cast<double>(rim);
        const double start = static_cast<double>(random.pair(PixelRandom::kChoice, 0).x) * spacing;
        for (int j = 0; j < rim; ++j) {
            const int t = std::min(border - 1, static_cast<int>(start + spacing * static_cast<double>(j)));
            const int cell = strata.borderCell(t);
            used[static_cast<size_t>(cell)] = 1;
            batch.push_back(cell);
        }
    }
    const int inner = size - rim;
    if (inner > 0) {
        const int cx = std::clamp(static_cast<int>(std::lround(std::sqrt(static_cast<double>(inner)))), 1, strata.nx);
        const int cy = std::clamp(inner / cx, 1, strata.ny);
        for (int by = 0; by < cy; ++by)
            for (int bx = 0; bx < cx; ++bx) {
                const int x0 = bx * strata.nx / cx, x1 = (bx + 1) * strata.nx / cx;
                const int y0 = by * strata.ny / cy, y1 = (by + 1) * strata.ny / cy;
                const int w = x1 - x0, cells = w * (y1 - y0);
                if (cells <= 0) continue;
                const uint64_t r = random.bits(PixelRandom::kChoice, static_cast<uint64_t>(1 + by * cx + bx));
                for (int probe = 0; probe < cells; ++probe) { // first unused cell from a random one
                    const int c = static_cast<int>((r + static_cast<uint64_t>(probe)) % static_cast<uint64_t>(cells));
                    const int cell = (y0 + c / w) * strata.nx + x0 + c % w;
                    if (used[static_cast<size_t>(cell)]) continue;
                    used[static_cast<size_t>(cell)] = 1;
                    batch.push_back(cell);
                    break;
                }
            }
    }
    for (int cell : batch) used[static_cast<size_t>(cell)] = 0;
}

// Estimated standard error of one pixel's stratified mean from its own samples (`values`, the
// scalar result of stratum k at index k). One sample per stratum gives no within-stratum
// variance, so strata are collapsed in pairs of neighbours (Cochran, "Sampling Techniques",
// 5A.12): E[(y_a - y_b)^2] = var_a + var_b + (mean_a - mean_b)^2, an over-estimate by the
// difference of the pair's means. Pairing along rows over-estimates an edge that crosses the
// rows, pairing along columns one that crosses the columns; the smaller of the two is kept. It
// still errs high: against the closed-form sphere shadow 1.14x the measured error at 64 rays and
// 1.21x at 1024; on contact and dragon-like 1.17x to 1.26x the error measured with two seeds.
// Samples outside the grid (N - nx*ny of them) are uniform: binomial variance of the pixel's mean.
double standardError(const Strata& strata, const std::vector<float>& values, double mean) {
    const int nx = strata.nx, ny = strata.ny;
    auto y = [&](int x, int row) { return static_cast<double>(values[static_cast<size_t>(row * nx + x)]); };
    auto squared = [](double d) { return d * d; };
    // Pairs (0, 1), (2, 3), ...; an odd last cell is paired with the one before it.
    double rows = 0.0, columns = 0.0;
    for (int row = 0; row < ny; ++row)
        for (int x = 0; x + 1 < nx; x += 2) {
            rows += squared(y(x, row) - y(x + 1, row));
            if (x + 3 == nx) rows += squared(y(x + 1, row) - y(x + 2, row));
        }
    for (int x = 0; x < nx; ++x)
        for (int row = 0; row + 1 < ny; row += 2) {
            columns += squared(y(x, row) - y(x, row + 1));
            if (row + 3 == ny) columns += squared(y(x, row + 1) - y(x, row + 2));
        }
    double variance = nx >= 2 && ny >= 2 ? std::min(rows, columns) : nx >= 2 ? rows : columns;
    const int extra = strata.count - strata.grid();
    variance += static_cast<double>(extra) * std::clamp(mean * (1.0 - mean), 0.0, 0.25);
    return std::sqrt(variance) / static_cast<double>(strata.count);
}

// Where one shadow ray goes: unit direction and length (infinite for directional lights).
struct ShadowRay {
    glm::vec3 direction;
    float length;
};

// Samples over the light's emitter as seen from one shaded point.
class EmitterSampler {
public:
    EmitterSampler(const LightInfo& light, glm::vec3 origin, float endOffset)
        : light_(light), origin_(origin), endOffset_(endOffset) {
        if (light.type == LightType::Directional) {
            axis_ = -light.direction;
            // 1 - cos(size) as 2 sin^2(size / 2): no cancellation for the small angles of the sun.
            const float s = std::sin(0.5f * light.size);
            oneMinusCosMax_ = 2.0f * s * s;
        } else {
            // The disc faces the shaded point (point light) or looks along the spot's axis.
            const glm::vec3 toPoint = origin - light.position;
            const float length = glm::length(toPoint);
            axis_ = light.type == LightType::Spot || length == 0.0f ? light.direction : toPoint / length;
        }
        orthonormalBasis(axis_, tangent_, bitangent_);
    }

    ShadowRay centre() const { return toward(light_.position); }

    // u in [0,1)^2 -> a ray to a point of the emitter, uniform in area (disc) or solid angle (cone).
    ShadowRay sample(glm::vec2 u) const {
        const glm::vec2 d = concentricDisc(u);
        if (light_.type == LightType::Directional) {
            // Uniform on the spherical cap of angular radius size: cos(theta) = 1 - r^2 (1 - cos max),
            // r^2 uniform in [0,1) on the concentric disc, phi kept from the disc point.
            const float r2 = glm::dot(d, d);
            const float cosTheta = 1.0f - r2 * oneMinusCosMax_;
            const float sinTheta = std::sqrt(std::max(0.0f, 1.0f - cosTheta * cosTheta));
            const float r = std::sqrt(r2);
            const glm::vec2 phi = r > 0.0f ? d / r : glm::vec2(1.0f, 0.0f);
            const glm::vec3 direction =
                cosTheta * axis_ + sinTheta * (phi.x * tangent_ + phi.y * bitangent_);
            return {glm::normalize(direction), kInfinity};
        }
        return toward(light_.position + light_.size * (d.x * tangent_ + d.y * bitangent_));
    }

private:
    ShadowRay toward(glm::vec3 target) const {
        if (light_.type == LightType::Directional) return {-light_.direction, kInfinity};
        const glm::vec3 toTarget = target - origin_;
        const float distance = glm::length(toTarget);
        if (distance == 0.0f) return {-light_.direction, 0.0f};
        // Stop short of the light by the same offset as at the surface: a lamp's own fixture
        // touching the light position does not shadow everything.
        return {toTarget / distance, std::max(0.0f, distance - endOffset_)};
    }

    const LightInfo& light_;
    glm::vec3 origin_;
    float endOffset_;
    glm::vec3 axis_{0.0f, 1.0f, 0.0f}, tangent_{1.0f, 0.0f, 0.0f}, bitangent_{0.0f, 0.0f, 1.0f};
    float oneMinusCosMax_ = 0.0f;
};

// ---------------------------------------------------------------------------------------------
// Geometry kept beside the BVH: Embree reads the positions and indices in place (shared
// buffers); normals and materials are ours, for primary hits and transmission.
struct MeshData {
    std::vector<glm::vec3> positions; // one element of padding: Embree loads vertices 16 bytes at a time
    std::vector<glm::vec3> normals;
    std::vector<glm::vec2> uvs;       // transmission textures are sampled at the hit's uv
    std::vector<uint32_t> indices;
    size_t vertexCount = 0;
    RTCScene scene = nullptr;         // instanced meshes only
};

// One per top-level geometry ID.
struct SurfaceRecord {
    const MeshData* mesh = nullptr;
    glm::mat4 model{1.0f};            // identity for flattened meshes (already in world space)
    glm::mat3 normalMatrix{1.0f};
    bool opaque = true;
    float alpha = 1.0f;               // translucent surfaces: the material's coverage and
    glm::vec3 transmission{0.0f};     // transmission colour, unclamped
    int texture = -1;                 // transmission texture (index into textures_): replaces both per texel
};

// kStreamFlags: every ray stream is traced with the default (incoherent) context flags. With
// RTC_INTERSECT_CONTEXT_FLAG_COHERENT, Embree 3.13.5 (Debian 12) spent minutes in one
// rtcOccluded1M call on `point-light` (lispsm's G-buffer after csm's, finite rays; seen in gdb) and
// made PointLight.CubeMapShadowsAgainstTheReference time out at 600 s; incoherent, the whole test
// takes about a second.
void initRay(RTCRay& ray, glm::vec3 origin, const ShadowRay& shadowRay, unsigned mask) {
    ray.org_x = origin.x;
    ray.org_y = origin.y;
    ray.org_z = origin.z;
    ray.tnear = 0.0f;
    ray.dir_x = shadowRay.direction.x;
    ray.dir_y = shadowRay.direction.y;
    ray.dir_z = shadowRay.direction.z;
    ray.time = 0.0f;
    ray.tfar = shadowRay.length;
    ray.mask = mask;
    ray.id = 0;
    ray.flags = 0;
}

// Runs worker(nextRow) on `threads` std::threads; each pulls rows with nextRow++ until the rows
// run out, so fast and slow rows even out. The first exception is rethrown here.
template <class Worker>
void parallelRows(int threads, Worker&& worker) {
    std::atomic<int> nextRow{0};
    std::exception_ptr failure;
    std::mutex failureMutex;
    auto run = [&]() {
        try {
            worker(nextRow);
        } catch (...) {
            std::lock_guard lock(failureMutex);
            if (!failure) failure = std::current_exception();
        }
    };
    std::vector<std::thread> pool;
    for (int i = 1; i < threads; ++i) pool.emplace_back(run);
    run();
    for (std::thread& thread : pool) thread.join();
    if (failure) std::rethrow_exception(failure);
}

// TraceControl (groundtruth.h): rows planned and done, and whether to stop taking rows.
void planRows(const ReferenceOptions& options, int rows) {
    if (options.control) options.control->rowsTotal += static_cast<uint64_t>(std::max(rows, 0));
}
void rowDone(const ReferenceOptions& options) {
    if (options.control) options.control->rowsDone.fetch_add(1, std::memory_order_relaxed);
}
bool stopRequested(const ReferenceOptions& options) { return options.control && options.control->cancelled(); }

int threadCount(int requested, int rows) {
    int threads = requested > 0 ? requested : static_cast<int>(std::thread::hardware_concurrency());
    return std::clamp(threads, 1, std::max(1, rows));
}

// ---------------------------------------------------------------------------------------------
class EmbreeGroundTruth final : public IGroundTruth {
public:
    EmbreeGroundTruth() {
        device_ = rtcNewDevice(nullptr);
        if (!device_) {
            deviceError_ = "rtcNewDevice failed (error " + std::to_string(rtcGetDeviceError(nullptr)) + ")";
            return;
        }
        rtcSetDeviceErrorFunction(device_, &EmbreeGroundTruth::onError, this);
    }

    ~EmbreeGroundTruth() override {
        releaseScene();
        if (device_) rtcReleaseDevice(device_);
    }

    EmbreeGroundTruth(const EmbreeGroundTruth&) = delete;
    EmbreeGroundTruth& operator=(const EmbreeGroundTruth&) = delete;

    void setScene(const Scene& scene) override {
        if (!device_) throw std::runtime_error("ground truth: " + deviceError_);
        releaseScene();
        deviceError_.clear();

        std::vector<int> uses(scene.meshes.size(), 0);
        for (size_t i = 0; i < scene.objects.size(); ++i) {
            const SceneObject& object = scene.objects[i];
            if (object.mesh >= scene.meshes.size())
                throw std::runtime_error("ground truth: objects[" + std::to_string(i) + "] ('" + object.name +
                                         "') uses mesh " + std::to_string(object.mesh) + " of " +
                                         std::to_string(scene.meshes.size()));
            ++uses[object.mesh];
        }
        for (size_t m = 0; m < scene.meshes.size(); ++m)
            for (const Vertex& vertex : scene.meshes[m].vertices)
                if (!finite(vertex.position))
                    throw std::runtime_error("ground truth: mesh " + std::to_string(m) + ": a vertex position is not finite");

        top_ = rtcNewScene(device_);
        // Robust: watertight traversal, no shadow ray slips between two triangles of a shared edge.
        rtcSetSceneFlags(top_, RTC_SCENE_FLAG_ROBUST);
        rtcSetSceneBuildQuality(top_, RTC_BUILD_QUALITY_HIGH); // built once, traced millions of times

        std::vector<MeshData*> shared(scene.meshes.size(), nullptr);
        glm::vec3 lower(kInfinity), upper(-kInfinity);
        for (size_t i = 0; i < scene.objects.size(); ++i) {
            const SceneObject& object = scene.objects[i];
            const Mesh& mesh = scene.meshes[object.mesh];
            validateMesh(mesh, object, i);
            if (mesh.indices.size() < 3) continue;

            for (const Vertex& v : mesh.vertices) {
                const glm::vec3 p(object.transform * glm::vec4(v.position, 1.0f));
                lower = glm::min(lower, p);
                upper = glm::max(upper, p);
            }

            SurfaceRecord record;
            const glm::mat3 normalMatrix = glm::transpose(glm::inverse(glm::mat3(object.transform)));
            RTCGeometry geometry;
            if (uses[object.mesh] > 1) {
                MeshData*& data = shared[object.mesh];
                if (!data) {
                    data = addMesh(mesh, glm::mat4(1.0f));
                    data->scene = rtcNewScene(device_);
                    rtcSetSceneFlags(data->scene, RTC_SCENE_FLAG_ROBUST);
                    rtcSetSceneBuildQuality(data->scene, RTC_BUILD_QUALITY_HIGH);
                    RTCGeometry triangles = newTriangleGeometry(*data);
                    rtcCommitGeometry(triangles);
                    rtcAttachGeometry(data->scene, triangles);
                    rtcReleaseGeometry(triangles);
                    rtcCommitScene(data->scene);
                }
                geometry = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_INSTANCE);
                rtcSetGeometryInstancedScene(geometry, data->scene);
                rtcSetGeometryTransform(geometry, 0, RTC_FORMAT_FLOAT4X4_COLUMN_MAJOR, &object.transform[0][0]);
                record.mesh = data;
                record.model = object.transform;
                record.normalMatrix = normalMatrix;
            } else {
                MeshData* data = addMesh(mesh, object.transform);
                geometry = newTriangleGeometry(*data);
                record.mesh = data;
            }
            rtcSetGeometryMask(geometry, kMaskVisible | (object.castsShadow ? kMaskCaster : 0u));
            rtcCommitGeometry(geometry);
            const unsigned id = rtcAttachGeometry(top_, geometry);
            rtcReleaseGeometry(geometry);

            const Material fallback;
            const Material& material = object.material < scene.materials.size() ? scene.materials[object.material] : fallback;
            record.opaque = !material.translucent();
            if (!record.opaque) {
                record.alpha = material.alpha;
                record.transmission = material.transmission;
                if (material.transmissionTexture >= 0 && size_t(material.transmissionTexture) < scene.textures.size()) {
                    record.texture = material.transmissionTexture;
                }
                if (object.castsShadow) anyTranslucentCaster_ = true;
            }
            if (surfaces_.size() <= id) surfaces_.resize(id + 1);
            surfaces_[id] = record;
        }
        textures_ = scene.textures;
        rtcCommitScene(top_);
        if (!deviceError_.empty()) {
            const std::string message = deviceError_;
            releaseScene();
            throw std::runtime_error("ground truth: Embree: " + message);
        }

        // The offset scales with the scene's size and with its distance from the origin (float
        // spacing grows with |p|).
        if (lower.x <= upper.x) {
            const float extent = std::max(glm::length(upper - lower),
                                          std::max(glm::length(lower), glm::length(upper)));
            rayOffset_ = 1e-4f * std::max(extent, 1e-3f);
        } else {
            rayOffset_ = 1e-4f;
        }
    }

    void trace(const GBufferView& gbuffer, const LightInfo& light, const ReferenceOptions& options,
               std::vector<glm::vec3>& visibility, ReferenceStats* stats) override {
        requireScene();
        validateLight(light);
        if (gbuffer.width < 0 || gbuffer.height < 0 ||
            (gbuffer.width * gbuffer.height > 0 && (!gbuffer.positions || !gbuffer.normals)))
            throw std::invalid_argument("ground truth: trace: G-buffer without positions or normals");
        const int width = gbuffer.width, height = gbuffer.height;
        const size_t pixels = static_cast<size_t>(width) * static_cast<size_t>(height);
        visibility.assign(pixels, glm::vec3(0.0f));
        ReferenceStats local;
        ReferenceStats& out = stats ? *stats : local;
        out = ReferenceStats{};
        for (size_t i = 0; i < pixels; ++i) out.tracedPixels += facesLight(gbuffer.positions[i], gbuffer.normals[i], light);

        const bool soft = options.mode == ReferenceOptions::Mode::Soft && light.size > 0.0f && options.samplesPerPixel > 1;
        if (!soft) {
            traceHard(gbuffer, light, options, visibility);
            out.refinedPixels = out.tracedPixels;
            out.shadowRays = out.tracedPixels;
            return;
        }
        traceSoft(gbuffer, light, options, visibility, out, stats != nullptr);
    }

    void tracePrimary(const glm::mat4& viewProjection, glm::vec3 cameraPos, int width, int height,
                      std::vector<glm::vec4>& positions, std::vector<glm::vec4>& normals) override {
        requireScene();
        width = std::max(width, 0);
        height = std::max(height, 0);
        const size_t pixels = static_cast<size_t>(width) * static_cast<size_t>(height);
        positions.assign(pixels, glm::vec4(0.0f));
        normals.assign(pixels, glm::vec4(0.0f));
        const glm::mat4 inverseViewProjection = glm::inverse(viewProjection);

        parallelRows(threadCount(0, height), [&](std::atomic<int>& nextRow) {
            std::vector<RTCRayHit> rayHits(static_cast<size_t>(std::max(width, 1)));
            RTCIntersectContext context;
            rtcInitIntersectContext(&context);   // incoherent: see kStreamFlags
            for (int row; (row = nextRow++) < height;) {
                for (int x = 0; x < width; ++x) {
                    // NDC z = 1 is the far plane in both GL (-1..1) and zero-to-one depth conventions.
                    const glm::vec2 ndc((static_cast<float>(x) + 0.5f) / static_cast<float>(width) * 2.0f - 1.0f,
                                        (static_cast<float>(row) + 0.5f) / static_cast<float>(height) * 2.0f - 1.0f);
                    const glm::vec4 farPoint = inverseViewProjection * glm::vec4(ndc, 1.0f, 1.0f);
                    const glm::vec3 direction = glm::normalize(glm::vec3(farPoint) / farPoint.w - cameraPos);
                    RTCRayHit& rayHit = rayHits[static_cast<size_t>(x)];
                    initRay(rayHit.ray, cameraPos, {direction, kInfinity}, kMaskVisible);
                    rayHit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
                    rayHit.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
                }
                rtcIntersect1M(top_, &context, rayHits.data(), static_cast<unsigned>(width), sizeof(RTCRayHit));
                for (int x = 0; x < width; ++x) {
                    const RTCRayHit& rayHit = rayHits[static_cast<size_t>(x)];
                    if (rayHit.hit.geomID == RTC_INVALID_GEOMETRY_ID) continue;
                    const size_t i = static_cast<size_t>(row) * static_cast<size_t>(width) + static_cast<size_t>(x);
                    surfacePoint(rayHit.hit, positions[i], normals[i]);
                }
            }
        });
    }

    float rayOffset() const override { return rayOffset_; }

private:
    // Where a pixel's shadow rays start: off the surface along the normal turned to the light.
    glm::vec3 shadowOrigin(const GBufferView& gbuffer, size_t i, const LightInfo& light, glm::vec3& n) const {
        const glm::vec3 p(gbuffer.positions[i]);
        n = glm::normalize(glm::vec3(gbuffer.normals[i]));
        if (glm::dot(n, directionToLight(light, p)) < 0.0f) n = -n; // face the light
        return p + n * rayOffset_;
    }

    // One ray per pixel to the light's centre; the rays of a row go to Embree as one stream.
    void traceHard(const GBufferView& gbuffer, const LightInfo& light, const ReferenceOptions& options,
                   std::vector<glm::vec3>& visibility) const {
        const int width = gbuffer.width, height = gbuffer.height;
        const bool coloured = options.model != TranslucencyModel::Opaque && anyTranslucentCaster_;
        planRows(options, height);
        parallelRows(threadCount(options.threads, height), [&](std::atomic<int>& nextRow) {
            std::vector<RTCRay> rays(static_cast<size_t>(std::max(width, 1)));
            std::vector<int> rayPixel(rays.size());
            RTCIntersectContext context;
            rtcInitIntersectContext(&context);
            // Hard rays of a row to one light are coherent, but the coherent stream mode is not
            // used (see kStreamFlags).
            for (int row; !stopRequested(options) && (row = nextRow++) < height; rowDone(options)) {
                const size_t rowStart = static_cast<size_t>(row) * static_cast<size_t>(width);
                int count = 0;
                for (int x = 0; x < width; ++x) {
                    const size_t i = rowStart + static_cast<size_t>(x);
                    if (!facesLight(gbuffer.positions[i], gbuffer.normals[i], light)) continue;
                    glm::vec3 n;
                    const glm::vec3 origin = shadowOrigin(gbuffer, i, light, n);
                    const EmitterSampler emitter(light, origin, rayOffset_);
                    if (coloured) {
                        visibility[i] = transmittance(origin, emitter.centre(), options.model, context);
                    } else {
                        initRay(rays[static_cast<size_t>(count)], origin, emitter.centre(), kMaskCaster);
                        rayPixel[static_cast<size_t>(count++)] = x;
                    }
                }
                if (count > 0) {
                    rtcOccluded1M(top_, &context, rays.data(), static_cast<unsigned>(count), sizeof(RTCRay));
                    for (int k = 0; k < count; ++k) // occluded rays come back with tfar = -inf
                        if (rays[static_cast<size_t>(k)].tfar >= 0.0f)
                            visibility[rowStart + static_cast<size_t>(rayPixel[static_cast<size_t>(k)])] = glm::vec3(1.0f);
                }
            }
        });
    }

    // Per-thread storage for the samples of one pixel.
    struct SampleBuffers {
        explicit SampleBuffers(int n)
            : rays(static_cast<size_t>(n)), slot(static_cast<size_t>(n)), results(static_cast<size_t>(n)),
              scalar(static_cast<size_t>(n)), used(static_cast<size_t>(n), 0) {
            batch.reserve(static_cast<size_t>(n));
        }
        std::vector<RTCRay> rays;
        std::vector<int> slot;          // rays[r] is sample slot[r] of the list traced
        std::vector<glm::vec3> results; // per sample of the list
        std::vector<float> scalar;      // per stratum: mean of the result's channels
        std::vector<uint8_t> used;      // chooseFirstBatch's scratch
        std::vector<int> batch;
    };

    // Traces strata list[0..count) of one pixel: results[j] is what sample list[j] lets through,
    // 0 for a sample below the surface's tangent plane (the surface itself hides that part of the
    // emitter, whether or not the receiver casts shadows). Returns the rays traced.
    uint64_t traceSamples(glm::vec3 origin, glm::vec3 n, const EmitterSampler& emitter, const PixelRandom& random,
                          const Strata& strata, const int* list, int count, bool coloured, TranslucencyModel model,
                          RTCIntersectContext& context, SampleBuffers& b) const {
        std::fill_n(b.results.begin(), count, glm::vec3(0.0f));
        int streamed = 0;
        uint64_t traced = 0;
        for (int j = 0; j < count; ++j) {
            const ShadowRay ray = emitter.sample(strata.sample(list[j], random));
            if (glm::dot(ray.direction, n) <= 0.0f) continue;
            ++traced;
            if (coloured) {
                b.results[static_cast<size_t>(j)] = transmittance(origin, ray, model, context);
            } else {
                initRay(b.rays[static_cast<size_t>(streamed)], origin, ray, kMaskCaster);
                b.slot[static_cast<size_t>(streamed++)] = j;
            }
        }
        if (streamed > 0) {
            // The rays of one pixel share an origin and nearly a direction: one coherent stream.
            rtcOccluded1M(top_, &context, b.rays.data(), static_cast<unsigned>(streamed), sizeof(RTCRay));
            for (int r = 0; r < streamed; ++r) // occluded rays come back with tfar = -inf
                if (b.rays[static_cast<size_t>(r)].tfar >= 0.0f) b.results[static_cast<size_t>(b.slot[static_cast<size_t>(r)])] = glm::vec3(1.0f);
        }
        return traced;
    }

    // The soft reference, uniform or adaptive.
    //
    // Uniform: every pixel facing the light traces all N strata (Strata), in index order.
    //
    // Adaptive (ReferenceOptions::adaptive), in three passes:
    //  1. every pixel traces its first batch (chooseFirstBatch: B of the N strata, half of them
    //     rays to the emitter's rim at even angular spacing, half one per block of a coarse grid
    //     over the emitter). A pixel is unanimous when every one of its B results is the same
    //     (0 or 1; in coloured mode the same rgb transmittance);
    //  2. the split pixels are dilated in image space: a pixel is refined when any pixel within
    //     refineRadius (square window) split, itself included;
    //  3. refined pixels trace all N strata in index order, exactly as the uniform pass does (the
    //     first batch is traced again: it is B rays, and the sum is then the uniform one bit for
    //     bit); the others keep their unanimous value.
    //
    // Why a unanimous pixel can stop: its value is wrong only if some part of the emitter is
    // blocked (or, for a shadowed pixel, visible) and no ray of B found it. Occluder and receiver
    // move continuously across the image, so the blocked part of the emitter enters through its
    // rim (at a neighbouring pixel) and grows inwards. The rim rays lie in the outermost ring of
    // strata (concentric radius above 1 - 2 / sqrt(N)), at most about 26 degrees apart at B = 32,
    // N = 1024: a straight occluder edge that reaches more than 9 % of the radius in from the rim
    // must hit one, so for certain it leaves unseen at most a sliver of 1.5 % of the emitter (9 %
    // at N = 64, 0.7 % at 4096). A thinner sliver is still found with a probability that grows
    // with it (the rays are jittered), the interior rays catch edges that reach further in, and
    // the neighbours, where the edge reaches further in, trace their own independent batches: one
    // split within refineRadius refines the pixel. Measured against uniform 1024 rays at
    // 1280x720: 0 stopped pixels differ on contact, 1 (by 1/1024) on dragon-like.
    //
    // What it can miss, honestly: (1) next to a straight edge, the sliver above (at most 1.5 % of
    // the emitter at N = 1024, and only where no neighbour within refineRadius split); (2) an
    // occluder, or a hole in one, whose image on the emitter is smaller than the gaps between
    // first-batch rays (about 0.45 of the emitter's radius at the rim, 0.5 inside at B = 32),
    // lying wholly inside the emitter's image, at pixels none of whose neighbours within
    // refineRadius had a batch ray blocked by it: a thin twig or a small hole far from the
    // receiver. Such a pixel keeps 1 (or 0) where the uniform reference says 1 - c, c at most
    // that occluder's share of the emitter (a disc that fits between the rays: about 5 %).
    void traceSoft(const GBufferView& gbuffer, const LightInfo& light, const ReferenceOptions& options,
                   std::vector<glm::vec3>& visibility, ReferenceStats& out, bool wantError) const {
        const int width = gbuffer.width, height = gbuffer.height;
        const size_t pixels = static_cast<size_t>(width) * static_cast<size_t>(height);
        const bool coloured = options.model != TranslucencyModel::Opaque && anyTranslucentCaster_;
        const Strata strata(options.samplesPerPixel);
        const int batchSize = std::clamp(options.firstBatch, 1, strata.count);
        const bool adaptive = options.adaptive && strata.nx >= 2 && strata.ny >= 2 && batchSize < strata.count;
        out.samplesPerPixel = strata.count;
        out.adaptive = adaptive;
        out.firstBatch = adaptive ? batchSize : 0;
        if (wantError) out.sampleError.assign(pixels, 0.0f);
        const int threads = threadCount(options.threads, height);
        std::vector<int> everyStratum(static_cast<size_t>(strata.count));
        for (int k = 0; k < strata.count; ++k) everyStratum[static_cast<size_t>(k)] = k;
        planRows(options, adaptive ? 2 * height : height);

        // Per pixel: 0 not traced (not facing the light), 1 unanimous first batch, 2 split first
        // batch, 3 to be traced with all N strata.
        enum : uint8_t { kSkip = 0, kUnanimous = 1, kSplit = 2, kRefine = 3 };
        std::vector<uint8_t> state(pixels, kSkip);
        for (size_t i = 0; i < pixels; ++i)
            if (facesLight(gbuffer.positions[i], gbuffer.normals[i], light)) state[i] = adaptive ? kUnanimous : kRefine;
        std::atomic<uint64_t> rays{0};

        auto context = [](RTCIntersectContext& c) {
            rtcInitIntersectContext(&c);   // incoherent: see kStreamFlags
        };
        if (adaptive) {
            parallelRows(threads, [&](std::atomic<int>& nextRow) {
                SampleBuffers b(strata.count);
                RTCIntersectContext c;
                context(c);
                uint64_t traced = 0;
                for (int row; !stopRequested(options) && (row = nextRow++) < height; rowDone(options)) {
                    for (int x = 0; x < width; ++x) {
                        const size_t i = static_cast<size_t>(row) * static_cast<size_t>(width) + static_cast<size_t>(x);
                        if (state[i] == kSkip) continue;
                        glm::vec3 n;
                        const glm::vec3 origin = shadowOrigin(gbuffer, i, light, n);
                        const EmitterSampler emitter(light, origin, rayOffset_);
                        const PixelRandom random(i, options.seed);
                        chooseFirstBatch(strata, batchSize, random, b.batch, b.used);
                        const int count = static_cast<int>(b.batch.size());
                        traced += traceSamples(origin, n, emitter, random, strata, b.batch.data(), count, coloured, options.model, c, b);
                        bool unanimous = true;
                        for (int j = 1; j < count && unanimous; ++j)
                            unanimous = b.results[static_cast<size_t>(j)] == b.results[0];
                        visibility[i] = b.results[0];
                        state[i] = unanimous ? kUnanimous : kSplit;
                    }
                }
                rays += traced;
            });

            // Dilation of the split pixels by refineRadius: along rows, then along columns.
            const int radius = std::clamp(options.refineRadius, 0, 64);
            std::vector<uint8_t> nearSplit(pixels, 0);
            for (int y = 0; y < height; ++y) {
                const size_t rowStart = static_cast<size_t>(y) * static_cast<size_t>(width);
                int last = -1 - radius - 1; // column of the last split pixel seen, looking ahead by radius
                for (int x = 0; x < width + radius; ++x) {
                    if (x < width && state[rowStart + static_cast<size_t>(x)] == kSplit) last = x;
                    const int target = x - radius;
                    if (target >= 0 && last >= target - radius) nearSplit[rowStart + static_cast<size_t>(target)] = 1;
                }
            }
            for (int x = 0; x < width; ++x) {
                int last = -1 - radius - 1;
                for (int y = 0; y < height + radius; ++y) {
                    if (y < height && nearSplit[static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x)]) last = y;
                    const int target = y - radius;
                    if (target < 0 || last < target - radius) continue;
                    const size_t i = static_cast<size_t>(target) * static_cast<size_t>(width) + static_cast<size_t>(x);
                    if (state[i] != kSkip) state[i] = kRefine;
                }
            }
        }

        for (size_t i = 0; i < pixels; ++i) out.refinedPixels += state[i] == kRefine;
        parallelRows(threads, [&](std::atomic<int>& nextRow) {
            SampleBuffers b(strata.count);
            RTCIntersectContext c;
            context(c);
            uint64_t traced = 0;
            for (int row; !stopRequested(options) && (row = nextRow++) < height; rowDone(options)) {
                for (int x = 0; x < width; ++x) {
                    const size_t i = static_cast<size_t>(row) * static_cast<size_t>(width) + static_cast<size_t>(x);
                    if (state[i] != kRefine) continue;
                    glm::vec3 n;
                    const glm::vec3 origin = shadowOrigin(gbuffer, i, light, n);
                    const EmitterSampler emitter(light, origin, rayOffset_);
                    const PixelRandom random(i, options.seed);
                    traced += traceSamples(origin, n, emitter, random, strata, everyStratum.data(), strata.count, coloured, options.model, c, b);
                    glm::vec3 sum(0.0f);
                    for (int k = 0; k < strata.count; ++k) sum += b.results[static_cast<size_t>(k)];
                    visibility[i] = sum / static_cast<float>(strata.count);
                    if (!wantError) continue;
                    for (int k = 0; k < strata.count; ++k) {
                        const glm::vec3& r = b.results[static_cast<size_t>(k)];
                        b.scalar[static_cast<size_t>(k)] = (r.r + r.g + r.b) / 3.0f;
                    }
                    const glm::vec3& v = visibility[i];
                    const double mean = (static_cast<double>(v.r) + v.g + v.b) / 3.0;
                    out.sampleError[i] = static_cast<float>(std::sqrt(2.0 / std::numbers::pi) * standardError(strata, b.scalar, mean));
                }
            }
            rays += traced;
        });
        out.shadowRays = rays.load();
    }

    // Embree may report from its build threads.
    static void onError(void* user, RTCError code, const char* message) {
        auto* self = static_cast<EmbreeGroundTruth*>(user);
        std::lock_guard lock(self->errorMutex_);
        if (self->deviceError_.empty())
            self->deviceError_ = (message ? std::string(message) : std::string("error")) + " (code " +
                                 std::to_string(static_cast<int>(code)) + ")";
    }

    void requireScene() const {
        if (!top_) throw std::logic_error("ground truth: setScene() was not called (or failed)");
    }

    static bool finite(glm::vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

    // Embree's builders assume finite input (an inf bound trips its assertions): refused here with
    // what is wrong, whoever the caller is. The scene parser already refuses such scenes.
    static void validateLight(const LightInfo& light) {
        auto fail = [](const std::string& what) {
            throw std::invalid_argument("ground truth: trace: the light's " + what +
                                        " (the reference needs finite light input)");
        };
        if (!finite(light.position)) fail("position is not finite");
        if (!finite(light.direction) || !(glm::length(light.direction) > 0.0f)) fail("direction is not a finite non-zero vector");
        if (!std::isfinite(light.size) || light.size < 0.0f) fail("size " + std::to_string(light.size) + " is not finite and >= 0");
        if (!std::isfinite(light.spotOuterAngle) || !std::isfinite(light.spotInnerAngle)) fail("spot angles are not finite");
    }

    static void validateMesh(const Mesh& mesh, const SceneObject& object, size_t index) {
        for (int c = 0; c < 4; ++c)
            if (!finite(glm::vec3(object.transform[c])) || !std::isfinite(object.transform[c][3]))
                throw std::runtime_error("ground truth: objects[" + std::to_string(index) + "] ('" + object.name +
                                         "'): transform is not finite");
        for (uint32_t vertex : mesh.indices)
            if (vertex >= mesh.vertices.size())
                throw std::runtime_error("ground truth: objects[" + std::to_string(index) + "] ('" + object.name +
                                         "'): index " + std::to_string(vertex) + " out of " +
                                         std::to_string(mesh.vertices.size()) + " vertices");
    }

    // Copies a mesh, transformed by `model`, into storage Embree can read in place.
    MeshData* addMesh(const Mesh& mesh, const glm::mat4& model) {
        auto data = std::make_unique<MeshData>();
        const glm::mat3 normalMatrix = glm::transpose(glm::inverse(glm::mat3(model)));
        data->vertexCount = mesh.vertices.size();
        data->positions.reserve(mesh.vertices.size() + 1);
        data->normals.reserve(mesh.vertices.size());
        for (const Vertex& v : mesh.vertices) {
            data->positions.emplace_back(model * glm::vec4(v.position, 1.0f));
            data->normals.push_back(normalMatrix * v.normal);
            data->uvs.push_back(v.uv);
        }
        data->positions.emplace_back(0.0f); // padding
        data->indices.assign(mesh.indices.begin(), mesh.indices.begin() + static_cast<std::ptrdiff_t>(mesh.indices.size() / 3 * 3));
        meshes_.push_back(std::move(data));
        return meshes_.back().get();
    }

    RTCGeometry newTriangleGeometry(MeshData& data) {
        RTCGeometry geometry = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
        rtcSetSharedGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, data.positions.data(), 0,
                                   sizeof(glm::vec3), data.vertexCount);
        rtcSetSharedGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, data.indices.data(), 0,
                                   3 * sizeof(uint32_t), data.indices.size() / 3);
        return geometry;
    }

    const SurfaceRecord& surfaceOf(const RTCHit& hit) const {
        return surfaces_[hit.instID[0] != RTC_INVALID_GEOMETRY_ID ? hit.instID[0] : hit.geomID];
    }

    // World position (barycentric on the triangle: exact to float rounding, unlike o + t d) and
    // interpolated vertex normal of a primary hit.
    void surfacePoint(const RTCHit& hit, glm::vec4& position, glm::vec4& normal) const {
        const SurfaceRecord& surface = surfaceOf(hit);
        const MeshData& mesh = *surface.mesh;
        const uint32_t* triangle = &mesh.indices[3 * static_cast<size_t>(hit.primID)];
        const float w = 1.0f - hit.u - hit.v;
        const glm::vec3 p = w * mesh.positions[triangle[0]] + hit.u * mesh.positions[triangle[1]] +
                            hit.v * mesh.positions[triangle[2]];
        glm::vec3 n = w * mesh.normals[triangle[0]] + hit.u * mesh.normals[triangle[1]] + hit.v * mesh.normals[triangle[2]];
        if (glm::dot(n, n) < 1e-12f) n = glm::vec3(hit.Ng_x, hit.Ng_y, hit.Ng_z); // mesh without normals
        position = glm::vec4(glm::vec3(surface.model * glm::vec4(p, 1.0f)), 1.0f);
        normal = glm::vec4(glm::normalize(surface.normalMatrix * n), 0.0f);
    }

    // Product of crossingFactor(model) of every caster the ray crosses, nearest first; 0 at the
    // first opaque one. Restarting just past each hit (rayOffset) crosses a surface once even where
    // the ray meets the shared edge of two of its triangles.
    glm::vec3 transmittance(glm::vec3 origin, const ShadowRay& shadowRay, TranslucencyModel model,
                            RTCIntersectContext& context) const {
        glm::vec3 throughput(1.0f);
        float tnear = 0.0f;
        for (int hits = 0; hits < kMaxTransmissionHits; ++hits) {
            RTCRayHit rayHit;
            initRay(rayHit.ray, origin, shadowRay, kMaskCaster);
            rayHit.ray.tnear = tnear;
            rayHit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
            rayHit.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
            rtcIntersect1(top_, &context, &rayHit);
            if (rayHit.hit.geomID == RTC_INVALID_GEOMETRY_ID) return throughput;
            const SurfaceRecord& surface = surfaceOf(rayHit.hit);
            if (surface.opaque) return glm::vec3(0.0f);
            if (surface.texture >= 0) {
                // The texel the GPU samples there: bilinear, repeat (sampleTexture, scene.h).
                const uint32_t* triangle = &surface.mesh->indices[3 * static_cast<size_t>(rayHit.hit.primID)];
                const std::vector<glm::vec2>& uv = surface.mesh->uvs;
                const float w = 1.0f - rayHit.hit.u - rayHit.hit.v;
                const glm::vec4 texel = sampleTexture(textures_[static_cast<size_t>(surface.texture)],
                                                      w * uv[triangle[0]] + rayHit.hit.u * uv[triangle[1]] +
                                                          rayHit.hit.v * uv[triangle[2]]);
                throughput *= crossingFactor(model, texel.a, glm::vec3(texel));
            } else {
                throughput *= crossingFactor(model, surface.alpha, surface.transmission);
            }
            if (throughput.r == 0.0f && throughput.g == 0.0f && throughput.b == 0.0f) return throughput;
            tnear = rayHit.ray.tfar + rayOffset_;
            if (tnear >= shadowRay.length) return throughput;
        }
        return throughput;
    }

    void releaseScene() {
        if (top_) rtcReleaseScene(top_);
        top_ = nullptr;
        for (auto& mesh : meshes_)
            if (mesh->scene) rtcReleaseScene(mesh->scene);
        meshes_.clear();
        surfaces_.clear();
        textures_.clear();
        anyTranslucentCaster_ = false;
        rayOffset_ = 1e-4f;
    }

    RTCDevice device_ = nullptr;
    RTCScene top_ = nullptr;
    std::string deviceError_;
    std::mutex errorMutex_;
    std::vector<std::unique_ptr<MeshData>> meshes_;
    std::vector<SurfaceRecord> surfaces_;
    std::vector<Texture> textures_;
    bool anyTranslucentCaster_ = false;
    float rayOffset_ = 1e-4f;
};

} // namespace
} // namespace shadowlab

extern "C" __attribute__((visibility("default"))) shadowlab::IGroundTruth* shadowlab_create_groundtruth(uint32_t abiVersion) {
    if (abiVersion != SHADOWLAB_GROUNDTRUTH_ABI_VERSION) return nullptr;
    return new shadowlab::EmbreeGroundTruth();
}
