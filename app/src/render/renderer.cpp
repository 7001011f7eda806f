// Host passes (see renderer.h).
#include "render/renderer.h"
#include "render/mesh_adjacency.h"

#include <algorithm>
#include <array>
#include <type_traits>

#include <glm/gtc/type_ptr.hpp>

#include "host_shared/contact_shadows_shared.h"
#include "host_shared/eye_blur_shared.h"
#include "render/bvh.h"
#include "shadowlab/frame_block.h"
#include "util/progress.h"
#include "host_shared/translucent_layers_shared.h"
#include "util/log.h"
#include "util/paths.h"

namespace shadowlab {
namespace {

using FrameUniforms = shared::frame::Frame;

// Keeps an object unless its box lies wholly on the negative side of a plane.
bool insidePlanes(const Bounds& box, const glm::vec4* planes, uint32_t count) {
    for (uint32_t i = 0; i < count; ++i) {
        const glm::vec3 n{planes[i]};
        const glm::vec3 farthest{n.x >= 0 ? box.max.x : box.min.x, n.y >= 0 ? box.max.y : box.min.y,
                                 n.z >= 0 ? box.max.z : box.min.z};
        if (glm::dot(n, farthest) + planes[i].w < 0.0f) return false;
    }
    return true;
}

GlTexture makeTexture(GLenum format, glm::ivec2 size, int samples, const char* label) {
    GLuint name = 0;
    if (samples > 0) {
        glCreateTextures(GL_TEXTURE_2D_MULTISAMPLE, 1, &name);
        glTextureStorage2DMultisample(name, samples, format, size.x, size.y, GL_TRUE);
    } else {
        glCreateTextures(GL_TEXTURE_2D, 1, &name);
        glTextureStorage2D(name, 1, format, size.x, size.y);
        glTextureParameteri(name, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTextureParameteri(name, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        glTextureParameteri(name, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        glTextureParameteri(name, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    }
    glObjectLabel(GL_TEXTURE, name, -1, label);
    return GlTexture(name);
}

bool attachMainTargets(GLuint fbo, FrameOutputs outputs, GLuint color, GLuint visibility, GLuint position, GLuint normal,
                       GLuint depth, const char* what, std::string& error) {
    glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, color, 0);
    glNamedFramebufferTexture(fbo, GL_DEPTH_STENCIL_ATTACHMENT, depth, 0);
    const GLenum buffers[] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2, GL_COLOR_ATTACHMENT3};
    if (outputs == FrameOutputs::Accuracy) {
        glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT1, visibility, 0);
        glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT2, position, 0);
        glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT3, normal, 0);
        glNamedFramebufferDrawBuffers(fbo, 4, buffers);
    } else {
        glNamedFramebufferDrawBuffers(fbo, 1, buffers);
    }
    glObjectLabel(GL_FRAMEBUFFER, fbo, -1, what);
    const GLenum status = glCheckNamedFramebufferStatus(fbo, GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE) {
        error = std::string(what) + " framebuffer is " + framebufferStatusName(status);
        return false;
    }
    return true;
}

int outputIndex(FrameOutputs outputs) { return outputs == FrameOutputs::Accuracy ? 1 : 0; }

} // namespace

bool Renderer::init(std::string& error) {
    GLuint name = 0;
    glCreateBuffers(1, &name);
    frameUniforms_.reset(name);
    glNamedBufferStorage(name, sizeof(FrameUniforms), nullptr, GL_DYNAMIC_STORAGE_BIT);
    glCreateVertexArrays(1, &name);
    emptyVao_.reset(name);
    glCreateSamplers(1, &name);
    presentSampler_.reset(name);
    // Compare mode off so depth maps (often set up for sampler2DShadow) can be viewed.
    glSamplerParameteri(name, GL_TEXTURE_COMPARE_MODE, GL_NONE);
    glSamplerParameteri(name, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glSamplerParameteri(name, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glSamplerParameteri(name, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glSamplerParameteri(name, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);

    // Host-owned samplers for techniques (SamplerKind order), so no technique changes sampling
    // state on its textures every frame.
    struct SamplerSetup {
        GLint minFilter, magFilter;
        bool compare;
    };
    const SamplerSetup setups[] = {{GL_NEAREST, GL_NEAREST, false},
                                   {GL_LINEAR, GL_LINEAR, false},
                                   {GL_LINEAR_MIPMAP_LINEAR, GL_LINEAR, false},
                                   {GL_NEAREST, GL_NEAREST, true},
                                   {GL_LINEAR, GL_LINEAR, true},
                                   {GL_NEAREST_MIPMAP_NEAREST, GL_NEAREST, false}};
    static_assert(std::extent_v<decltype(setups)> == std::extent_v<decltype(samplers_)>);
    for (size_t i = 0; i < std::size(setups); ++i) {
        glCreateSamplers(1, &name);
        samplers_[i].reset(name);
        glSamplerParameteri(name, GL_TEXTURE_MIN_FILTER, setups[i].minFilter);
        glSamplerParameteri(name, GL_TEXTURE_MAG_FILTER, setups[i].magFilter);
        glSamplerParameteri(name, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        glSamplerParameteri(name, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
        glSamplerParameteri(name, GL_TEXTURE_WRAP_R, GL_CLAMP_TO_EDGE);
        glSamplerParameteri(name, GL_TEXTURE_COMPARE_MODE, setups[i].compare ? GL_COMPARE_REF_TO_TEXTURE : GL_NONE);
        glSamplerParameteri(name, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
    }

    presentProgram_ = shaders_.build(hostShaderRequest("fullscreen.vert", "present.frag", "host present"), error);
    if (!presentProgram_) return false;
    prepassProgram_ = shaders_.build(hostShaderRequest("main.vert", "camera_prepass.frag", "host camera pre-pass"), error);
    if (!prepassProgram_) return false;
    // The main pass's own vertex stage, no fragment stage: bit-identical depth.
    depthOnlyProgram_ = shaders_.build(hostShaderRequest("main.vert", "", "host depth pre-pass"), error);
    if (!depthOnlyProgram_) return false;
    eyeBlurProgram_ = shaders_.build(hostShaderRequest("fullscreen.vert", "eye_blur.frag", "host eye-space blur"), error);
    if (!eyeBlurProgram_) return false;
    contactProgram_ = shaders_.build(hostShaderRequest("fullscreen.vert", "contact_shadows.frag", "host contact shadows"), error);
    overdraw_.create();
    return contactProgram_ != 0;
}

GLuint Renderer::sampler(SamplerKind kind) const {
    const auto index = size_t(kind);
    return index < std::size(samplers_) ? samplers_[index].get() : 0u;
}

// The meshes' vertices and indices, each straight from its mesh into one buffer (no combined copy
// on the CPU), in chunks with progress: a 4096 x 4096 sphere is a gigabyte that llvmpipe copies
// for tens of seconds (util/progress.h; Ctrl-C throws Interrupted between chunks).
void Renderer::uploadSceneGeometry(const Scene& scene) {
    size_t vertexCount = 0, indexCount = 0;
    meshRanges_.clear();
    for (const Mesh& mesh : scene.meshes) {
        meshRanges_.push_back({uint32_t(indexCount), uint32_t(mesh.indices.size()), int32_t(vertexCount)});
        vertexCount += mesh.vertices.size();
        indexCount += mesh.indices.size();
    }
    constexpr size_t kChunkBytes = size_t(64) << 20;
    const size_t totalBytes = vertexCount * sizeof(Vertex) + indexCount * sizeof(uint32_t);
    Progress progress("uploading the scene's geometry", (totalBytes + kChunkBytes - 1) / kChunkBytes, "chunks of 64 MiB");
    size_t uploaded = 0;
    auto upload = [&](GlBuffer& buffer, size_t bytes, auto member) {
        GLuint name = 0;
        glCreateBuffers(1, &name);
        buffer.reset(name);
        glNamedBufferStorage(name, GLsizeiptr(std::max<size_t>(1, bytes)), nullptr, GL_DYNAMIC_STORAGE_BIT);
        size_t offset = 0;
        for (const Mesh& mesh : scene.meshes) {
            const auto& data = mesh.*member;
            const auto* bytesOf = reinterpret_cast<const uint8_t*>(data.data());
            const size_t size = data.size() * sizeof(data[0]);
            for (size_t done = 0; done < size; done += kChunkBytes) {
                const size_t chunk = std::min(kChunkBytes, size - done);
                glNamedBufferSubData(name, GLintptr(offset + done), GLsizeiptr(chunk), bytesOf + done);
                uploaded += chunk;
                progress.stepOrThrow(uploaded / kChunkBytes);
            }
            offset += size;
        }
    };
    upload(vertexBuffer_, vertexCount * sizeof(Vertex), &Mesh::vertices);
    upload(indexBuffer_, indexCount * sizeof(uint32_t), &Mesh::indices);
    progress.step((totalBytes + kChunkBytes - 1) / kChunkBytes);
}

void Renderer::setScene(const Scene& scene) {
    scene_ = &scene;
    overdraw_.discardPending();   // counts of the previous scene
    adjacencyRanges_.clear();   // rebuilt on the first adjacency draw of this scene
    meshClosed_.clear();
    adjacencyReady_ = false;
    adjacencySceneReady_ = false;
    adjacencyBatches_.clear();
    adjacencyScene_ = {};
    for (GlBuffer& buffer : rayTracingBuffers_) buffer.reset();
    rayTracing_ = {};
    rayTracingBuilt_ = false;
    uploadSceneGeometry(scene);
    GLuint name = 0;
    glCreateVertexArrays(1, &name);
    sceneVao_.reset(name);
    glVertexArrayVertexBuffer(name, 0, vertexBuffer_.get(), 0, sizeof(Vertex));
    glVertexArrayElementBuffer(name, indexBuffer_.get());
    glEnableVertexArrayAttrib(name, 0);
    glEnableVertexArrayAttrib(name, 1);
    glEnableVertexArrayAttrib(name, 2);
    glVertexArrayAttribFormat(name, 0, 3, GL_FLOAT, GL_FALSE, offsetof(Vertex, position));
    glVertexArrayAttribFormat(name, 1, 3, GL_FLOAT, GL_FALSE, offsetof(Vertex, normal));
    glVertexArrayAttribFormat(name, 2, 2, GL_FLOAT, GL_FALSE, offsetof(Vertex, uv));
    for (GLuint attribute = 0; attribute < 3; ++attribute) glVertexArrayAttribBinding(name, attribute, 0);

    // Material textures. The same image may serve as base colour (sRGB-encoded) and as
    // transmission (linear), so it is uploaded in the format of each use.
    auto upload = [](const Texture& texture, GLenum format) {
        GLuint id = 0;
        glCreateTextures(GL_TEXTURE_2D, 1, &id);
        glTextureStorage2D(id, 1, format, texture.width, texture.height);
        glTextureSubImage2D(id, 0, 0, 0, texture.width, texture.height, GL_RGBA, GL_UNSIGNED_BYTE, texture.rgba.data());
        glTextureParameteri(id, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
        glTextureParameteri(id, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        glTextureParameteri(id, GL_TEXTURE_WRAP_S, GL_REPEAT);
        glTextureParameteri(id, GL_TEXTURE_WRAP_T, GL_REPEAT);
        glObjectLabel(GL_TEXTURE, id, -1, texture.name.c_str());
        return GlTexture(id);
    };
    transmissionTextures_.clear();
    baseColorTextures_.clear();
    transmissionTextures_.resize(scene.textures.size());
    baseColorTextures_.resize(scene.textures.size());
    for (const Material& material : scene.materials) {
        const auto t = size_t(material.transmissionTexture), b = size_t(material.baseColorTexture);
        if (material.transmissionTexture >= 0 && !transmissionTextures_[t]) transmissionTextures_[t] = upload(scene.textures[t], GL_RGBA8);
        if (material.baseColorTexture >= 0 && !baseColorTextures_[b]) baseColorTextures_[b] = upload(scene.textures[b], GL_SRGB8_ALPHA8);
    }
    if (!whiteTexture_) {
        const Texture white{"white", 1, 1, {255, 255, 255, 255}};
        whiteTexture_ = upload(white, GL_RGBA8);
    }

    // Transforms of every object in one buffer (std430 mirror of ObjectTransform in common.glsl).
    struct ObjectTransform {
        glm::mat4 model;
        glm::mat4 normalMatrix;
    };
    std::vector<ObjectTransform> transforms;
    transforms.reserve(scene.objects.size());
    batches_.clear();
    opaqueBatches_.clear();
    batchOfObject_.clear();
    for (uint32_t i = 0; i < scene.objects.size(); ++i) {
        const SceneObject& object = scene.objects[i];
        transforms.push_back({object.transform, glm::mat4(glm::transpose(glm::inverse(glm::mat3(object.transform))))});
        if (scene.materials[object.material].translucent()) {   // drawn one by one, sorted
            batches_.push_back({i, 1, object.mesh, object.material});
            batchOfObject_.push_back(uint32_t(batches_.size() - 1));
            continue;
        }
        const bool extends = !batches_.empty() && batches_.back().mesh == object.mesh &&
                             batches_.back().material == object.material &&
                             batches_.back().firstObject + batches_.back().count == i &&
                             scene.objects[batches_.back().firstObject].castsShadow == object.castsShadow &&
                             scene.objects[batches_.back().firstObject].receivesShadow == object.receivesShadow &&
                             !scene.materials[scene.objects[batches_.back().firstObject].material].translucent();
        if (extends) {
            ++batches_.back().count;
        } else {
            batches_.push_back({i, 1, object.mesh, object.material});
            opaqueBatches_.push_back(uint32_t(batches_.size() - 1));
        }
        batchOfObject_.push_back(uint32_t(batches_.size() - 1));
    }
    glCreateBuffers(1, &name);
    objectTransforms_.reset(name);
    glNamedBufferStorage(name, GLsizeiptr(std::max<size_t>(1, transforms.size()) * sizeof(ObjectTransform)),
                         transforms.empty() ? nullptr : transforms.data(), 0);
    drawOrder_.reserve(scene.objects.size());
}

bool Renderer::resize(glm::ivec2 size, int msaaSamples, std::string& error) {
    size = glm::max(size, glm::ivec2(1));
    if (size == size_ && msaaSamples == msaaSamples_ && mainFbo_[0]) return true;
    size_ = size;
    msaaSamples_ = msaaSamples;
    accuracyCurrent_ = false;
    color_ = makeTexture(GL_RGBA16F, size, 0, "main colour (linear)");
    visibility_ = makeTexture(GL_RGBA16F, size, 0, "main visibility");
    position_ = makeTexture(GL_RGBA32F, size, 0, "main world position");
    normal_ = makeTexture(GL_RGBA16F, size, 0, "main world normal");
    depth_ = makeTexture(GL_DEPTH24_STENCIL8, size, 0, "main depth");
    GLuint name = 0;
    const char* labels[2][2] = {{"main (colour)", "main (accuracy)"}, {"main MSAA (colour)", "main MSAA (accuracy)"}};
    for (FrameOutputs outputs : {FrameOutputs::Colour, FrameOutputs::Accuracy}) {
        const int o = outputIndex(outputs);
        glCreateFramebuffers(1, &name);
        mainFbo_[o].reset(name);
        if (!attachMainTargets(name, outputs, color_.get(), visibility_.get(), position_.get(), normal_.get(),
                               depth_.get(), labels[0][o], error))
            return false;
        msFbo_[o].reset();
    }
    msColor_.reset();
    msVisibility_.reset();
    msPosition_.reset();
    msNormal_.reset();
    msDepth_.reset();
    if (msaaSamples > 0) {
        msColor_ = makeTexture(GL_RGBA16F, size, msaaSamples, "main colour MSAA");
        msVisibility_ = makeTexture(GL_RGBA16F, size, msaaSamples, "main visibility MSAA");
        msPosition_ = makeTexture(GL_RGBA32F, size, msaaSamples, "main position MSAA");
        msNormal_ = makeTexture(GL_RGBA16F, size, msaaSamples, "main normal MSAA");
        msDepth_ = makeTexture(GL_DEPTH24_STENCIL8, size, msaaSamples, "main depth MSAA");
        for (FrameOutputs outputs : {FrameOutputs::Colour, FrameOutputs::Accuracy}) {
            const int o = outputIndex(outputs);
            glCreateFramebuffers(1, &name);
            msFbo_[o].reset(name);
            if (!attachMainTargets(name, outputs, msColor_.get(), msVisibility_.get(), msPosition_.get(),
                                   msNormal_.get(), msDepth_.get(), labels[1][o], error))
                return false;
        }
    }
    if (prepassDepthFbo_) allocatePrepassTargets(prepassFull_);
    if (eyeBlurTermFbo_) allocateEyeBlurTargets();
    if (contactFbo_) allocateContactTargets();
    if (layerFbo_[0]) allocateLayerTargets();
    displayColor_ = makeTexture(GL_RGBA8, size, 0, "display");
    glCreateFramebuffers(1, &name);
    displayFbo_.reset(name);
    glNamedFramebufferTexture(name, GL_COLOR_ATTACHMENT0, displayColor_.get(), 0);
    const GLenum status = glCheckNamedFramebufferStatus(name, GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE) {
        error = "display framebuffer is " + framebufferStatusName(status);
        return false;
    }
    return true;
}

void Renderer::setView(const CameraInfo& camera, const LightInfo& light) {
    camera_ = camera;
    camera_.viewport = size_;
    light_ = light;
    FrameUniforms u{};
    u.uView = camera_.view;
    u.uProjection = camera_.projection;
    u.uViewProjection = camera_.viewProjection;
    u.uCameraPosition = glm::vec4(camera_.position, 1.0f);
    u.uLightPosition = glm::vec4(light_.position, float(static_cast<uint32_t>(light_.type)));
    u.uLightDirection = glm::vec4(glm::normalize(light_.direction), light_.size);
    u.uLightColor = glm::vec4(light_.color, 1.0f);
    u.uLightSpot = glm::vec4(std::cos(light_.spotOuterAngle), std::cos(light_.spotInnerAngle), 0.0f, 0.0f);
    u.uAmbient = glm::vec4(scene_ ? scene_->ambient : glm::vec3(0.0f), 1.0f);
    u.uViewport = glm::vec4(float(size_.x), float(size_.y), 1.0f / float(size_.x), 1.0f / float(size_.y));
    glNamedBufferSubData(frameUniforms_.get(), 0, sizeof(u), &u);
    glBindBufferBase(GL_UNIFORM_BUFFER, 0, frameUniforms_.get());
}

Bounds Renderer::bounds(DrawSet set) const {
    return scene_ ? scene_->worldBounds(set) : Bounds{glm::vec3(-1.0f), glm::vec3(1.0f)};
}

uint32_t Renderer::objectCount() const { return scene_ ? uint32_t(scene_->objects.size()) : 0u; }

const ObjectInfo* Renderer::objects() const {
    return scene_ && scene_->objectInfo.size() == scene_->objects.size() ? scene_->objectInfo.data() : nullptr;
}

void Renderer::drawBatch(uint32_t firstObject, uint32_t count, uint32_t mesh, uint32_t material, DrawPrimitive primitive) {
    const Material& m = scene_->materials[material];
    glUniform1i(0, GLint(firstObject));
    glUniform4f(2, m.baseColor.r, m.baseColor.g, m.baseColor.b, m.alpha);
    glUniform4f(3, m.transmission.r, m.transmission.g, m.transmission.b, 1.0f);
    glUniform4f(4, m.specular.r, m.specular.g, m.specular.b, m.shininess);
    const bool transmissionMap = m.transmissionTexture >= 0, baseColorMap = m.baseColorTexture >= 0;
    glUniform4i(5, transmissionMap ? 1 : 0, baseColorMap ? 1 : 0, 0, 0);
    glBindTextureUnit(1, transmissionMap ? transmissionTextures_[size_t(m.transmissionTexture)].get() : whiteTexture_.get());
    glBindTextureUnit(2, baseColorMap ? baseColorTextures_[size_t(m.baseColorTexture)].get() : whiteTexture_.get());
    const bool adjacency = primitive == DrawPrimitive::TrianglesAdjacency;
    if (adjacency) glUniform1i(6, meshClosed_[mesh]);
    const MeshRange& range = adjacency ? adjacencyRanges_[mesh] : meshRanges_[mesh];
    glDrawElementsInstancedBaseVertex(adjacency ? GL_TRIANGLES_ADJACENCY : GL_TRIANGLES, GLsizei(range.indexCount),
                                      GL_UNSIGNED_INT,
                                      reinterpret_cast<const void*>(uintptr_t(range.firstIndex) * sizeof(uint32_t)),
                                      GLsizei(count), range.baseVertex);
}

void Renderer::prepareAdjacency() {
    if (!scene_ || adjacencyReady_) return;
    adjacencyReady_ = true;
    std::vector<uint32_t> indices;
    for (size_t m = 0; m < scene_->meshes.size(); ++m) {
        MeshAdjacency adjacency = buildMeshAdjacency(scene_->meshes[m]);
        adjacencyRanges_.push_back({uint32_t(indices.size()), uint32_t(adjacency.indices.size()), meshRanges_[m].baseVertex});
        meshClosed_.push_back(adjacency.closed ? 1 : 0);
        indices.insert(indices.end(), adjacency.indices.begin(), adjacency.indices.end());
    }
    GLuint name = 0;
    glCreateBuffers(1, &name);
    adjacencyIndices_.reset(name);
    glNamedBufferStorage(name, GLsizeiptr(std::max<size_t>(1, indices.size() * sizeof(uint32_t))),
                         indices.empty() ? nullptr : indices.data(), 0);
    glObjectLabel(GL_BUFFER, name, -1, "scene triangles with adjacency");
    // The scene's vertex layout with the adjacency indices.
    glCreateVertexArrays(1, &name);
    adjacencyVao_.reset(name);
    glVertexArrayVertexBuffer(name, 0, vertexBuffer_.get(), 0, sizeof(Vertex));
    glVertexArrayElementBuffer(name, adjacencyIndices_.get());
    for (GLuint attribute = 0; attribute < 3; ++attribute) {
        glEnableVertexArrayAttrib(name, attribute);
        glVertexArrayAttribBinding(name, attribute, 0);
    }
    glVertexArrayAttribFormat(name, 0, 3, GL_FLOAT, GL_FALSE, offsetof(Vertex, position));
    glVertexArrayAttribFormat(name, 1, 3, GL_FLOAT, GL_FALSE, offsetof(Vertex, normal));
    glVertexArrayAttribFormat(name, 2, 2, GL_FLOAT, GL_FALSE, offsetof(Vertex, uv));
}

const AdjacencyScene& Renderer::adjacencyScene() {
    if (!scene_ || adjacencySceneReady_) return adjacencyScene_;
    prepareAdjacency();
    adjacencySceneReady_ = true;
    AdjacencyScene& a = adjacencyScene_;
    a = {};
    // Consecutive caster batches of one mesh merge into one run (batches also split by material,
    // which the silhouettes do not care about).
    for (const Batch& batch : batches_) {
        if (!scene_->inSet(scene_->objects[batch.firstObject], DrawSet::Casters)) continue;
        const MeshRange& range = adjacencyRanges_[batch.mesh];
        const AdjacencyBatch run{batch.firstObject, batch.count, range.firstIndex / 6, range.indexCount / 6,
                                 range.baseVertex, meshClosed_[batch.mesh]};
        AdjacencyBatch* last = adjacencyBatches_.empty() ? nullptr : &adjacencyBatches_.back();
        if (last && last->firstObject + last->objectCount == run.firstObject && last->firstTriangle == run.firstTriangle &&
            last->triangleCount == run.triangleCount && last->baseVertex == run.baseVertex)
            last->objectCount += run.objectCount;
        else
            adjacencyBatches_.push_back(run);
        a.triangles += uint64_t(run.objectCount) * run.triangleCount;
        if (run.closed) a.closedTriangles += uint64_t(run.objectCount) * run.triangleCount;
    }
    a.vertices = vertexBuffer_.get();
    a.indices = adjacencyIndices_.get();
    a.transforms = objectTransforms_.get();
    a.batches = adjacencyBatches_.data();
    a.batchCount = uint32_t(adjacencyBatches_.size());
    return a;
}

void Renderer::bindSceneGeometry(GLuint program) {
    glUseProgram(program);
    glBindVertexArray(sceneVao_.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, objectTransforms_.get());
    glBindBufferBase(GL_UNIFORM_BUFFER, 0, frameUniforms_.get());
}

void Renderer::drawObject(uint32_t index, GLuint program) {
    if (!scene_ || index >= scene_->objects.size()) return;
    bindSceneGeometry(program);
    const SceneObject& object = scene_->objects[index];
    drawBatch(index, 1, object.mesh, object.material);
}

void Renderer::drawScene(const DrawRequest& request, GLuint program) {
    if (!scene_) return;
    bindSceneGeometry(program);
    const DrawPrimitive primitive = request.primitive;
    if (primitive == DrawPrimitive::TrianglesAdjacency) {
        prepareAdjacency();
        glBindVertexArray(adjacencyVao_.get());
    }
    const bool culled = request.cullPlanes && request.cullPlaneCount > 0;
    if (request.order == DrawOrder::Scene && !culled) {
        // A batch shares its objects' flags, so its first object decides for all of it.
        for (const Batch& batch : batches_)
            if (scene_->inSet(scene_->objects[batch.firstObject], request.set))
                drawBatch(batch.firstObject, batch.count, batch.mesh, batch.material, primitive);
        return;
    }
    // The objects that pass, sorted if asked, then drawn in runs of consecutive objects of one
    // batch (still instanced where order and culling leave a run together).
    collectDrawOrder(request);
    for (size_t k = 0; k < drawOrder_.size();) {
        const uint32_t first = drawOrder_[k].second;
        size_t end = k + 1;
        while (end < drawOrder_.size() && drawOrder_[end].second == drawOrder_[end - 1].second + 1 &&
               batchOfObject_[drawOrder_[end].second] == batchOfObject_[first])
            ++end;
        const SceneObject& object = scene_->objects[first];
        drawBatch(first, uint32_t(end - k), object.mesh, object.material, primitive);
        k = end;
    }
}

void Renderer::collectDrawOrder(const DrawRequest& request) {
    drawOrder_.clear();
    const std::vector<ObjectInfo>& info = scene_->objectInfo;
    const bool culled = request.cullPlanes && request.cullPlaneCount > 0;
    const glm::vec3 reference{request.orderReference};
    const bool fromPoint = request.orderReference.w != 0.0f;
    for (const Batch& batch : batches_) {
        if (!scene_->inSet(scene_->objects[batch.firstObject], request.set)) continue;
        for (uint32_t i = batch.firstObject; i < batch.firstObject + batch.count; ++i) {
            if (culled && !insidePlanes(info[i].bounds, request.cullPlanes, request.cullPlaneCount)) continue;
            const float key = request.order == DrawOrder::Scene ? float(i)
                              : fromPoint                       ? glm::length(info[i].center - reference)
                                                                : glm::dot(info[i].center, reference);
            drawOrder_.push_back({request.order == DrawOrder::BackToFront ? -key : key, i});
        }
    }
    if (request.order != DrawOrder::Scene)
        std::stable_sort(drawOrder_.begin(), drawOrder_.end(), [](auto& a, auto& b) { return a.first < b.first; });
}

void Renderer::drawFullscreenTriangle() {
    glBindVertexArray(emptyVao_.get());
    glDrawArrays(GL_TRIANGLES, 0, 3);
}

GLuint Renderer::mainFramebuffer(FrameOutputs outputs) const {
    const int o = outputIndex(outputs);
    return msaaSamples_ > 0 ? msFbo_[o].get() : mainFbo_[o].get();
}

void Renderer::clearMainTargets(GLuint fbo, FrameOutputs outputs, bool depth) {
    const glm::vec3 bg = scene_ ? scene_->background : glm::vec3(0.0f);
    const float background[4] = {bg.r, bg.g, bg.b, 1.0f};
    const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    glClearNamedFramebufferfv(fbo, GL_COLOR, 0, background);
    if (outputs == FrameOutputs::Accuracy)
        for (GLint buffer = 1; buffer < 4; ++buffer) glClearNamedFramebufferfv(fbo, GL_COLOR, buffer, zero);
    if (depth) glClearNamedFramebufferfi(fbo, GL_DEPTH_STENCIL, 0, 1.0f, 0);
}

void Renderer::mainDepthPrepass(FrameOutputs outputs) {
    applyDefaultState();
    const GLuint fbo = mainFramebuffer(outputs);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    glClearNamedFramebufferfi(fbo, GL_DEPTH_STENCIL, 0, 1.0f, 0);
    const GLuint program = shaders_.program(depthOnlyProgram_);
    glUseProgram(program);
    bindSceneGeometry(program);
    const bool counting = beginOverdrawCount();
    for (uint32_t index : opaqueBatches_) {
        const Batch& batch = batches_[index];
        drawBatch(batch.firstObject, batch.count, batch.mesh, batch.material);
    }
    if (counting) overdraw_.end();
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    depthPrepassed_ = true;
}

void Renderer::beginMainPass(GLuint program, FrameOutputs outputs) {
    const GLuint fbo = mainFramebuffer(outputs);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glViewport(0, 0, size_.x, size_.y);
    glDisable(GL_FRAMEBUFFER_SRGB);   // colour stays linear; the present pass encodes
    glEnable(GL_DEPTH_TEST);
    // After a depth pre-pass only the nearest surface passes, and depth is final already.
    glDepthFunc(depthPrepassed_ ? GL_EQUAL : GL_LESS);
    glDepthMask(depthPrepassed_ ? GL_FALSE : GL_TRUE);
    glDisable(GL_BLEND);
    glDisable(GL_STENCIL_TEST);
    if (depthPrepassed_) {
        // Surfaces whose depths tie (coplanar, or a huge depth range's quantised far end) all pass
        // EQUAL, where LESS kept the first drawn: a stencil count lets only the first fragment of
        // a sample through, the same one LESS keeps (the same draw order), so the image is that of
        // the main pass without the pre-pass, and no sample is shaded twice. The pre-pass cleared
        // the stencil to 0.
        glEnable(GL_STENCIL_TEST);
        glStencilMask(0xFF);
        glStencilFunc(GL_EQUAL, 0, 0xFF);
        glStencilOp(GL_KEEP, GL_KEEP, GL_INCR);
    }
    glDisable(GL_POLYGON_OFFSET_FILL);
    glDisable(GL_CULL_FACE);          // planes are single-sided quads seen from both sides
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    clearMainTargets(fbo, outputs, !depthPrepassed_);
    bindSceneGeometry(program);
    glUniform1i(SHADOWLAB_LIGHTING_LOCATION, lighting_);
    if (eyeBlurRead_) {
        glBindTextureUnit(shared::eye_blur::kEyeBlurTermUnit, eyeBlurTerm_[0].get());
        glBindSampler(shared::eye_blur::kEyeBlurTermUnit, 0);
        glUniform1i(SHADOWLAB_EYE_BLUR_READ_LOCATION, 1);
    }
    // Set every pass, on or off: the value is the program's, and stays from an earlier frame.
    glUniform1i(SHADOWLAB_CONTACT_READ_LOCATION, contactRead_ ? 1 : 0);
    if (contactRead_) {
        glBindTextureUnit(shared::contact_shadows::kContactTermUnit, contactTerm_.get());
        glBindSampler(shared::contact_shadows::kContactTermUnit, 0);
    }
}

void Renderer::allocateContactTargets() {
    contactTerm_ = makeTexture(GL_R8, size_, 0, "contact shadows: term");
    GLuint name = 0;
    glCreateFramebuffers(1, &name);
    contactFbo_.reset(name);
    glObjectLabel(GL_FRAMEBUFFER, name, -1, "contact shadows");
    glNamedFramebufferTexture(name, GL_COLOR_ATTACHMENT0, contactTerm_.get(), 0);
    const GLenum status = glCheckNamedFramebufferStatus(name, GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE) logError("contact shadows framebuffer is " + framebufferStatusName(status));
}

void Renderer::contactShadows(const ContactSettings& settings) {
    if (!contactFbo_) allocateContactTargets();
    applyDefaultState();
    glDisable(GL_DEPTH_TEST);
    glDepthMask(GL_FALSE);
    glBindFramebuffer(GL_FRAMEBUFFER, contactFbo_.get());
    glViewport(0, 0, size_.x, size_.y);
    glUseProgram(shaders_.program(contactProgram_));
    glBindBufferBase(GL_UNIFORM_BUFFER, 0, frameUniforms_.get());
    const glm::mat4 inverseViewProjection = glm::inverse(camera_.viewProjection);
    glUniformMatrix4fv(SHADOWLAB_CONTACT_INVERSE_VP_LOCATION, 1, GL_FALSE, glm::value_ptr(inverseViewProjection));
    glUniform4f(SHADOWLAB_CONTACT_PARAMS_LOCATION, settings.length, settings.thickness, float(settings.steps), settings.jitter);
    glBindTextureUnit(shared::contact_shadows::kContactDepthUnit, prepassDepth_.get());
    glBindSampler(shared::contact_shadows::kContactDepthUnit, 0);
    drawFullscreenTriangle();
    glBindTextureUnit(shared::contact_shadows::kContactDepthUnit, 0);
    resetPipelineState();
}

void Renderer::allocateEyeBlurTargets() {
    GLuint name = 0;
    const char* labels[2] = {"eye-space blur: term and result", "eye-space blur: along x"};
    for (int i = 0; i < 2; ++i) {
        eyeBlurTerm_[i] = makeTexture(GL_RGBA32F, size_, 0, labels[i]);
        glCreateFramebuffers(1, &name);
        eyeBlurFbo_[i].reset(name);
        glNamedFramebufferTexture(name, GL_COLOR_ATTACHMENT0, eyeBlurTerm_[i].get(), 0);
        glObjectLabel(GL_FRAMEBUFFER, name, -1, labels[i]);
    }
    eyeBlurDepth_ = makeTexture(GL_DEPTH24_STENCIL8, size_, 0, "eye-space blur: depth");
    glCreateFramebuffers(1, &name);
    eyeBlurTermFbo_.reset(name);
    glObjectLabel(GL_FRAMEBUFFER, name, -1, "eye-space blur: term pass");
    glNamedFramebufferTexture(name, GL_COLOR_ATTACHMENT0, eyeBlurTerm_[0].get(), 0);
    glNamedFramebufferTexture(name, GL_DEPTH_STENCIL_ATTACHMENT, eyeBlurDepth_.get(), 0);
    for (GLuint fbo : {eyeBlurTermFbo_.get(), eyeBlurFbo_[0].get(), eyeBlurFbo_[1].get()}) {
        const GLenum status = glCheckNamedFramebufferStatus(fbo, GL_FRAMEBUFFER);
        if (status != GL_FRAMEBUFFER_COMPLETE) logError("eye-space blur framebuffer is " + framebufferStatusName(status));
    }
}

void Renderer::beginEyeBlurTerm(GLuint program) {
    if (!eyeBlurTermFbo_) allocateEyeBlurTargets();
    const GLuint fbo = eyeBlurTermFbo_.get();
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glViewport(0, 0, size_.x, size_.y);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);   // as the main pass: planes are seen from both sides
    const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};   // a = 0: no surface
    glClearNamedFramebufferfv(fbo, GL_COLOR, 0, zero);
    glClearNamedFramebufferfi(fbo, GL_DEPTH_STENCIL, 0, 1.0f, 0);
    bindSceneGeometry(program);
}

void Renderer::drawOpaque(GLuint program) {
    if (!scene_) return;
    bindSceneGeometry(program);
    for (uint32_t index : opaqueBatches_) {
        const Batch& batch = batches_[index];
        drawBatch(batch.firstObject, batch.count, batch.mesh, batch.material);
    }
}

void Renderer::eyeBlur(float width, float referenceDepth) {
    if (!eyeBlurTermFbo_) allocateEyeBlurTargets();
    applyDefaultState();
    glDisable(GL_DEPTH_TEST);
    glDepthMask(GL_FALSE);
    glViewport(0, 0, size_.x, size_.y);
    glUseProgram(shaders_.program(eyeBlurProgram_));
    glUniform1f(1, width);
    glUniform1f(2, referenceDepth > 0.0f ? referenceDepth : camera_.nearPlane);
    glBindSampler(shared::eye_blur::kEyeBlurTermUnit, 0);
    // Along x: term -> [1]; along y: [1] -> term.
    for (int pass = 0; pass < 2; ++pass) {
        glBindFramebuffer(GL_FRAMEBUFFER, eyeBlurFbo_[1 - pass].get());
        glBindTextureUnit(shared::eye_blur::kEyeBlurTermUnit, eyeBlurTerm_[pass].get());
        glUniform2i(0, pass == 0 ? 1 : 0, pass == 0 ? 0 : 1);
        drawFullscreenTriangle();
    }
    glBindTextureUnit(shared::eye_blur::kEyeBlurTermUnit, 0);
    resetPipelineState();
}

bool Renderer::beginOverdrawCount() {
    if (!overdrawArmed_) return false;
    overdrawArmed_ = false;
    const uint64_t samples = uint64_t(size_.x) * uint64_t(size_.y) * uint64_t(std::max(msaaSamples_, 1));
    return overdraw_.begin(samples);
}

void Renderer::drawMainPassObjects(GLuint program, FrameOutputs outputs) {
    if (!scene_) return;
    // After a pre-pass (EQUAL) only the visible surfaces pass: the pre-pass counted already.
    const bool counting = !depthPrepassed_ && beginOverdrawCount();
    drawOpaque(program);
    if (counting) overdraw_.end();
    glDisable(GL_STENCIL_TEST);   // the pre-pass's shade-once count is for the opaque surfaces only
    if (opaqueBatches_.size() == batches_.size()) return;
    // Translucent surfaces: blended colour, back to front from the camera by their bounds'
    // centres, without touching the G-buffer or depth, so the accuracy targets hold the opaque
    // surface behind them (translucent receivers are measured by translucentLayer()).
    drawTranslucent(program, [this, program, outputs] { setMainTranslucentState(program, outputs); });
    const GLuint gbufferTargets = outputs == FrameOutputs::Accuracy ? 4 : 1;
    for (GLuint attachment = 1; attachment < gbufferTargets; ++attachment)
        glColorMaski(attachment, GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glDisablei(GL_BLEND, 0);
    glDepthMask(GL_TRUE);
}

void Renderer::setMainTranslucentState(GLuint program, FrameOutputs outputs) {
    glBindFramebuffer(GL_FRAMEBUFFER, mainFramebuffer(outputs));
    glViewport(0, 0, size_.x, size_.y);
    glDisable(GL_FRAMEBUFFER_SRGB);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_FALSE);
    glDisable(GL_CULL_FACE);
    glDisable(GL_STENCIL_TEST);
    glEnablei(GL_BLEND, 0);
    glBlendFunci(0, GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    const GLuint gbufferTargets = outputs == FrameOutputs::Accuracy ? 4 : 1;
    for (GLuint attachment = 1; attachment < gbufferTargets; ++attachment)
        glColorMaski(attachment, GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    bindSceneGeometry(program);
    glUniform1i(SHADOWLAB_LIGHTING_LOCATION, lighting_);
    // The blurred term holds the opaque surfaces only: translucent ones call shadowTerm().
    if (eyeBlurRead_) glUniform1i(SHADOWLAB_EYE_BLUR_READ_LOCATION, 0);
    // The contact term, too: it comes from the opaque depth.
    glUniform1i(SHADOWLAB_CONTACT_READ_LOCATION, 0);
}

void Renderer::drawTranslucent(GLuint program, const std::function<void()>& setState) {
    DrawRequest translucent;
    translucent.set = DrawSet::Translucent;
    translucent.order = DrawOrder::BackToFront;
    translucent.orderReference = glm::vec4(camera_.position, 1.0f);
    if (!translucentHook_) {
        setState();
        drawScene(translucent, program);
        return;
    }
    // One object at a time with the technique's hook before each (SHADOWLAB_EXT_TRANSLUCENT_DRAWS).
    // The order is copied first: the hook draws through drawScene, which reuses drawOrder_.
    collectDrawOrder(translucent);
    translucentOrder_.clear();
    for (const auto& [key, object] : drawOrder_) translucentOrder_.push_back(object);
    for (const uint32_t object : translucentOrder_) {
        translucentHook_(object);
        setState();
        drawObject(object, program);
    }
    translucentHook_(kTranslucentDrawsDone);
    setState();
}

void Renderer::allocateLayerTargets() {
    layerVisibility_ = makeTexture(GL_RGBA16F, size_, 0, "translucent layer visibility");
    layerPosition_ = makeTexture(GL_RGBA32F, size_, 0, "translucent layer world position");
    layerNormal_ = makeTexture(GL_RGBA16F, size_, 0, "translucent layer world normal");
    const char* labels[2] = {"translucent layer depth (even)", "translucent layer depth (odd)"};
    for (int i = 0; i < 2; ++i) {
        layerDepth_[i] = makeTexture(GL_DEPTH_COMPONENT32F, size_, 0, labels[i]);
        GLuint name = 0;
        glCreateFramebuffers(1, &name);
        layerFbo_[i].reset(name);
        glObjectLabel(GL_FRAMEBUFFER, name, -1, labels[i]);
        // Location 0 (the lit colour) goes nowhere; 1-3 as the accuracy targets.
        glNamedFramebufferTexture(name, GL_COLOR_ATTACHMENT1, layerVisibility_.get(), 0);
        glNamedFramebufferTexture(name, GL_COLOR_ATTACHMENT2, layerPosition_.get(), 0);
        glNamedFramebufferTexture(name, GL_COLOR_ATTACHMENT3, layerNormal_.get(), 0);
        glNamedFramebufferTexture(name, GL_DEPTH_ATTACHMENT, layerDepth_[i].get(), 0);
        const GLenum buffers[] = {GL_NONE, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2, GL_COLOR_ATTACHMENT3};
        glNamedFramebufferDrawBuffers(name, 4, buffers);
        const GLenum status = glCheckNamedFramebufferStatus(name, GL_FRAMEBUFFER);
        if (status != GL_FRAMEBUFFER_COMPLETE) logError(std::string(labels[i]) + " framebuffer is " + framebufferStatusName(status));
    }
}

void Renderer::beginTranslucentLayer(int k) {
    if (!layerFbo_[0]) allocateLayerTargets();   // on first use; resize() reallocates
    const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    const GLuint fbo = layerFbo_[k % 2].get();
    for (GLint buffer = 1; buffer < 4; ++buffer) glClearNamedFramebufferfv(fbo, GL_COLOR, buffer, zero);
    glClearNamedFramebufferfv(fbo, GL_DEPTH, 0, std::array<float, 1>{1.0f}.data());
    // Layer 0 peels behind "nothing": the previous depth is 0 everywhere.
    if (k == 0) glClearNamedFramebufferfv(layerFbo_[1].get(), GL_DEPTH, 0, std::array<float, 1>{0.0f}.data());
}

void Renderer::setTranslucentLayerState(int k, GLuint program) {
    glBindFramebuffer(GL_FRAMEBUFFER, layerFbo_[k % 2].get());
    glViewport(0, 0, size_.x, size_.y);
    glDisable(GL_FRAMEBUFFER_SRGB);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);   // the nearest surface behind the previous layer wins
    glDepthMask(GL_TRUE);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);
    glDisable(GL_STENCIL_TEST);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    using namespace shared::translucent_layers;
    glBindTextureUnit(kPeelPreviousDepthUnit, layerDepth_[(k + 1) % 2].get());
    glBindSampler(kPeelPreviousDepthUnit, 0);
    glBindTextureUnit(kPeelOpaqueDepthUnit, depth_.get());
    glBindSampler(kPeelOpaqueDepthUnit, 0);
    bindSceneGeometry(program);
    glUniform1i(SHADOWLAB_LIGHTING_LOCATION, lighting_);
}

GLuint Renderer::layerTarget(MainTarget which) const {
    return which == MainTarget::Visibility ? layerVisibility_.get()
           : which == MainTarget::Position ? layerPosition_.get()
           : which == MainTarget::Normal   ? layerNormal_.get()
                                           : 0u;
}

void Renderer::applyDefaultState() {
    resetPipelineState();
    for (GLuint unit = 4; unit < 16; ++unit) glBindSampler(unit, 0);
    glBindBufferBase(GL_UNIFORM_BUFFER, 0, frameUniforms_.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, objectTransforms_.get());
    glUseProgram(0);
}

void Renderer::resetPipelineState() {
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, size_.x, size_.y);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);   // a pass counting into depth or stencil only may leave it off
    glDisable(GL_DEPTH_CLAMP);
    glDisable(GL_BLEND);
    glBlendEquation(GL_FUNC_ADD);
    glBlendFunc(GL_ONE, GL_ZERO);
    glDisable(GL_CULL_FACE);
    glCullFace(GL_BACK);
    glFrontFace(GL_CCW);
    glDisable(GL_STENCIL_TEST);
    glStencilMask(0xFF);
    glStencilFunc(GL_ALWAYS, 0, 0xFF);
    glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
    glDisable(GL_SCISSOR_TEST);
    for (GLenum i = 0; i < 8; ++i) glDisable(GL_CLIP_DISTANCE0 + i);
    glDisable(GL_POLYGON_OFFSET_FILL);
    glDisable(GL_POLYGON_OFFSET_LINE);
    glDisable(GL_POLYGON_OFFSET_POINT);
    glPolygonOffset(0.0f, 0.0f);
    glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
    glDisable(GL_RASTERIZER_DISCARD);
    glDisable(GL_SAMPLE_ALPHA_TO_COVERAGE);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glDisable(GL_FRAMEBUFFER_SRGB);
}

void Renderer::allocatePrepassTargets(bool full) {
    prepassDepth_ = makeTexture(GL_DEPTH24_STENCIL8, size_, 0, "camera pre-pass depth");
    GLuint name = 0;
    glCreateFramebuffers(1, &name);
    prepassDepthFbo_.reset(name);
    glObjectLabel(GL_FRAMEBUFFER, name, -1, "camera pre-pass (depth only)");
    glNamedFramebufferTexture(name, GL_DEPTH_STENCIL_ATTACHMENT, prepassDepth_.get(), 0);
    glNamedFramebufferDrawBuffer(name, GL_NONE);
    glNamedFramebufferReadBuffer(name, GL_NONE);
    GLenum status = glCheckNamedFramebufferStatus(name, GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE) logError("camera pre-pass framebuffer (depth only) is " + framebufferStatusName(status));
    // The stencil's view (CameraPrepass::stencil): its own sampling mode, the depth's storage.
    glGenTextures(1, &name);
    glTextureView(name, GL_TEXTURE_2D, prepassDepth_.get(), GL_DEPTH24_STENCIL8, 0, 1, 0, 1);
    prepassStencil_.reset(name);
    glObjectLabel(GL_TEXTURE, name, -1, "camera pre-pass stencil (view)");
    glTextureParameteri(name, GL_DEPTH_STENCIL_TEXTURE_MODE, GL_STENCIL_INDEX);
    glTextureParameteri(name, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(name, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    prepassDepthOnly_ = {sizeof(CameraPrepass), prepassDepth_.get(), 0, 0, 0, size_, prepassStencil_.get()};
    prepassFull_ = full;
    if (!full) return;   // the colour targets (20 bytes a pixel) only when a technique needs them
    prepassPosition_ = makeTexture(GL_RGBA32F, size_, 0, "camera pre-pass world position");
    prepassNormal_ = makeTexture(GL_RGBA16F, size_, 0, "camera pre-pass world normal");
    prepassObjectId_ = makeTexture(GL_R32UI, size_, 0, "camera pre-pass object id");
    glCreateFramebuffers(1, &name);
    prepassFbo_.reset(name);
    glObjectLabel(GL_FRAMEBUFFER, name, -1, "camera pre-pass");
    glNamedFramebufferTexture(name, GL_COLOR_ATTACHMENT0, prepassPosition_.get(), 0);
    glNamedFramebufferTexture(name, GL_COLOR_ATTACHMENT1, prepassNormal_.get(), 0);
    glNamedFramebufferTexture(name, GL_COLOR_ATTACHMENT2, prepassObjectId_.get(), 0);
    glNamedFramebufferTexture(name, GL_DEPTH_STENCIL_ATTACHMENT, prepassDepth_.get(), 0);
    const GLenum buffers[] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2};
    glNamedFramebufferDrawBuffers(name, 3, buffers);
    status = glCheckNamedFramebufferStatus(name, GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE) logError("camera pre-pass framebuffer is " + framebufferStatusName(status));
    prepass_ = {sizeof(CameraPrepass), prepassDepth_.get(), prepassPosition_.get(), prepassNormal_.get(),
                prepassObjectId_.get(), size_, prepassStencil_.get()};
}

const RayTracingScene& Renderer::rayTracing() {
    if (rayTracingBuilt_ || !scene_) return rayTracing_;
    const bvh::Bvh tree = bvh::build(*scene_);
    auto upload = [&](GlBuffer& buffer, const void* data, size_t bytes, const char* label) {
        GLuint name = 0;
        glCreateBuffers(1, &name);
        glNamedBufferStorage(name, GLsizeiptr(bytes), data, 0);
        glObjectLabel(GL_BUFFER, name, -1, label);
        buffer.reset(name);
        return name;
    };
    RayTracingScene& r = rayTracing_;
    r = {};
    r.nodes = upload(rayTracingBuffers_[0], tree.nodes.data(), tree.nodes.size() * sizeof(bvh::Node), "bvh nodes");
    r.triangles = upload(rayTracingBuffers_[1], tree.triangles.data(), tree.triangles.size() * sizeof(bvh::Triangle), "bvh triangles");
    r.uvs = upload(rayTracingBuffers_[2], tree.uvs.data(), tree.uvs.size() * sizeof(bvh::UvRecord), "bvh uvs");
    r.materials = upload(rayTracingBuffers_[3], tree.materials.data(), tree.materials.size() * sizeof(bvh::MaterialRecord), "bvh materials");
    r.texels = upload(rayTracingBuffers_[4], tree.texels.data(), tree.texels.size() * sizeof(uint32_t), "bvh texels");
    r.nodeCount = uint32_t(tree.nodes.size());
    r.triangleCount = uint32_t(tree.triangleCount);
    r.materialCount = uint32_t(tree.materials.size());
    r.depth = uint32_t(tree.depth);
    r.rayOffset = tree.rayOffset;
    r.buildMilliseconds = float(tree.buildSeconds * 1000.0);
    r.bytes = tree.bytes();
    rayTracingBuilt_ = true;
    return r;
}

void Renderer::cameraPrepass(PrepassKind kind) {
    const bool full = kind == PrepassKind::Full;
    if (!prepassDepthFbo_ || (full && !prepassFull_)) allocatePrepassTargets(full || prepassFull_);
    const GLuint fbo = full ? prepassFbo_.get() : prepassDepthFbo_.get();
    applyDefaultState();
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    if (full) {
        const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
        const GLuint noObject[4] = {0, 0, 0, 0};
        glClearNamedFramebufferfv(fbo, GL_COLOR, 0, zero);
        glClearNamedFramebufferfv(fbo, GL_COLOR, 1, zero);
        glClearNamedFramebufferuiv(fbo, GL_COLOR, 2, noObject);
    }
    glClearNamedFramebufferfi(fbo, GL_DEPTH_STENCIL, 0, 1.0f, 0);
    // Depth only: main.vert without a fragment stage (invariant gl_Position: the same depths).
    const GLuint program = shaders_.program(full ? prepassProgram_ : depthOnlyProgram_);
    bindSceneGeometry(program);
    for (uint32_t index : opaqueBatches_) {
        const Batch& batch = batches_[index];
        drawBatch(batch.firstObject, batch.count, batch.mesh, batch.material);
    }
}

void Renderer::endMainPass(FrameOutputs outputs) {
    depthPrepassed_ = false;
    accuracyCurrent_ = outputs == FrameOutputs::Accuracy;
    if (msaaSamples_ <= 0) return;
    // Resolve each attachment written; float targets average their samples (edges of the
    // G-buffer are therefore approximate with MSAA: accuracy runs use MSAA off).
    const int o = outputIndex(outputs);
    const int attachments = outputs == FrameOutputs::Accuracy ? 4 : 1;
    for (int attachment = 0; attachment < attachments; ++attachment) {
        glNamedFramebufferReadBuffer(msFbo_[o].get(), GL_COLOR_ATTACHMENT0 + GLenum(attachment));
        const GLenum draw = GL_COLOR_ATTACHMENT0 + GLenum(attachment);
        glNamedFramebufferDrawBuffers(mainFbo_[o].get(), 1, &draw);
        glBlitNamedFramebuffer(msFbo_[o].get(), mainFbo_[o].get(), 0, 0, size_.x, size_.y, 0, 0, size_.x, size_.y,
                               GL_COLOR_BUFFER_BIT, GL_NEAREST);
    }
    const GLenum buffers[] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2, GL_COLOR_ATTACHMENT3};
    glNamedFramebufferDrawBuffers(mainFbo_[o].get(), attachments, buffers);
}

GLuint Renderer::target(MainTarget which) const {
    switch (which) {
    case MainTarget::Color: return color_.get();
    case MainTarget::Visibility: return visibility_.get();
    case MainTarget::Position: return position_.get();
    case MainTarget::Normal: return normal_.get();
    }
    return 0;
}

void Renderer::present(PresentMode mode, GLuint texture, GLuint framebuffer, glm::ivec2 viewport, glm::vec2 range,
                       glm::ivec2 origin) {
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
    glViewport(origin.x, origin.y, viewport.x, viewport.y);
    glDisable(GL_FRAMEBUFFER_SRGB);   // present.frag encodes sRGB itself
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_STENCIL_TEST);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glUseProgram(shaders_.program(presentProgram_));
    glUniform1i(0, static_cast<int>(mode));
    glUniform2f(1, range.x, range.y);
    glBindTextureUnit(0, texture);
    glBindSampler(0, presentSampler_.get());
    drawFullscreenTriangle();
    glBindSampler(0, 0);
}

Image Renderer::readDisplay() const {
    Image image;
    image.width = size_.x;
    image.height = size_.y;
    image.channels = 4;
    image.pixels.resize(size_t(size_.x) * size_t(size_.y) * 4);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glGetTextureImage(displayColor_.get(), 0, GL_RGBA, GL_UNSIGNED_BYTE, GLsizei(image.pixels.size()), image.pixels.data());
    return image;
}

std::vector<glm::vec4> Renderer::readTarget(MainTarget which) const {
    if (which != MainTarget::Color && !accuracyCurrent_)
        logError("reading a main target the last frame did not write (render it with FrameOutputs::Accuracy)");
    std::vector<glm::vec4> pixels(size_t(size_.x) * size_t(size_.y));
    glGetTextureImage(target(which), 0, GL_RGBA, GL_FLOAT, GLsizei(pixels.size() * sizeof(glm::vec4)), pixels.data());
    return pixels;
}

void Renderer::uploadDisplay(const Image& image) {
    if (image.width != size_.x || image.height != size_.y || image.channels != 4) return;
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTextureSubImage2D(displayColor_.get(), 0, 0, 0, size_.x, size_.y, GL_RGBA, GL_UNSIGNED_BYTE, image.pixels.data());
}

} // namespace shadowlab
