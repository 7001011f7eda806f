// ImGui's draw lists through the host's GL (see imgui_gl.h).
#include "ui/imgui_gl.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace shadowlab {
namespace {

constexpr const char* kVertexShader = R"(#version 450 core
layout(location = 0) in vec2 aPosition;
layout(location = 1) in vec2 aUv;
layout(location = 2) in vec4 aColor;
layout(location = 0) uniform mat4 uProjection;
out vec2 vUv;
out vec4 vColor;
void main() {
    vUv = aUv;
    vColor = aColor;
    gl_Position = uProjection * vec4(aPosition, 0.0, 1.0);
}
)";

constexpr const char* kFragmentShader = R"(#version 450 core
in vec2 vUv;
in vec4 vColor;
layout(binding = 0) uniform sampler2D uTexture;
out vec4 outColor;
void main() { outColor = vColor * texture(uTexture, vUv); }
)";

bool compile(GLuint shader, const char* source, std::string& error) {
    glShaderSource(shader, 1, &source, nullptr);
    glCompileShader(shader);
    GLint ok = 0;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (ok) return true;
    char log[1024] = {};
    glGetShaderInfoLog(shader, sizeof(log), nullptr, log);
    error = std::string("UI shader: ") + log;
    return false;
}

} // namespace

bool ImGuiGlRenderer::init(std::string& error) {
    const GLuint vs = glCreateShader(GL_VERTEX_SHADER), fs = glCreateShader(GL_FRAGMENT_SHADER);
    const bool compiled = compile(vs, kVertexShader, error) && compile(fs, kFragmentShader, error);
    if (compiled) {
        program_.reset(glCreateProgram());
        glAttachShader(program_.get(), vs);
        glAttachShader(program_.get(), fs);
        glLinkProgram(program_.get());
    }
    glDeleteShader(vs);
    glDeleteShader(fs);
    if (!compiled) return false;
    GLint linked = 0;
    glGetProgramiv(program_.get(), GL_LINK_STATUS, &linked);
    if (!linked) {
        error = "UI shader: link failed";
        return false;
    }
    GLuint name = 0;
    glCreateVertexArrays(1, &name);
    vao_.reset(name);
    glCreateBuffers(1, &name);
    vertices_.reset(name);
    glCreateBuffers(1, &name);
    indices_.reset(name);
    const GLuint vao = vao_.get();
    glVertexArrayVertexBuffer(vao, 0, vertices_.get(), 0, sizeof(ImDrawVert));
    glVertexArrayElementBuffer(vao, indices_.get());
    const GLuint offsets[3] = {GLuint(offsetof(ImDrawVert, pos)), GLuint(offsetof(ImDrawVert, uv)), GLuint(offsetof(ImDrawVert, col))};
    for (GLuint a = 0; a < 3; ++a) {
        glEnableVertexArrayAttrib(vao, a);
        glVertexArrayAttribBinding(vao, a, 0);
    }
    glVertexArrayAttribFormat(vao, 0, 2, GL_FLOAT, GL_FALSE, offsets[0]);
    glVertexArrayAttribFormat(vao, 1, 2, GL_FLOAT, GL_FALSE, offsets[1]);
    glVertexArrayAttribFormat(vao, 2, 4, GL_UNSIGNED_BYTE, GL_TRUE, offsets[2]);
    ImGui::GetIO().BackendRendererName = "shadowlab host GL";
    ImGui::GetIO().BackendFlags |= ImGuiBackendFlags_RendererHasVtxOffset;
    createFontTexture();
    return true;
}

void ImGuiGlRenderer::createFontTexture() {
    unsigned char* pixels = nullptr;
    int width = 0, height = 0;
    ImGui::GetIO().Fonts->GetTexDataAsRGBA32(&pixels, &width, &height);
    GLuint name = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &name);
    font_.reset(name);
    glTextureStorage2D(name, 1, GL_RGBA8, width, height);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTextureSubImage2D(name, 0, 0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, pixels);
    glTextureParameteri(name, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(name, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    ImGui::GetIO().Fonts->SetTexID(reinterpret_cast<ImTextureID>(static_cast<intptr_t>(name)));
}

void ImGuiGlRenderer::render(const ImDrawData* data, GLuint framebuffer) {
    const int width = int(data->DisplaySize.x * data->FramebufferScale.x);
    const int height = int(data->DisplaySize.y * data->FramebufferScale.y);
    if (width <= 0 || height <= 0 || data->CmdListsCount == 0) return;
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
    glViewport(0, 0, width, height);
    glEnable(GL_BLEND);
    glBlendEquation(GL_FUNC_ADD);
    glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    glDisable(GL_CULL_FACE);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_STENCIL_TEST);
    glDisable(GL_FRAMEBUFFER_SRGB);   // ImGui's colours are display-referred already
    glEnable(GL_SCISSOR_TEST);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glUseProgram(program_.get());
    const float l = data->DisplayPos.x, r = l + data->DisplaySize.x, t = data->DisplayPos.y, b = t + data->DisplaySize.y;
    const float projection[16] = {2.0f / (r - l), 0, 0, 0, 0, 2.0f / (t - b), 0, 0, 0, 0, -1, 0,
                                  (r + l) / (l - r), (t + b) / (b - t), 0, 1};
    glUniformMatrix4fv(0, 1, GL_FALSE, projection);
    glBindVertexArray(vao_.get());
    glBindSampler(0, 0);
    const ImVec2 offset = data->DisplayPos, scale = data->FramebufferScale;
    for (int n = 0; n < data->CmdListsCount; ++n) {
        const ImDrawList* list = data->CmdLists[n];
        // Buffers grow to the largest frame seen; the same two objects every frame.
        const size_t vertexBytes = size_t(list->VtxBuffer.Size) * sizeof(ImDrawVert);
        const size_t indexBytes = size_t(list->IdxBuffer.Size) * sizeof(ImDrawIdx);
        if (vertexBytes > vertexBytes_) {
            vertexBytes_ = vertexBytes * 2;
            glNamedBufferData(vertices_.get(), GLsizeiptr(vertexBytes_), nullptr, GL_STREAM_DRAW);
        }
        if (indexBytes > indexBytes_) {
            indexBytes_ = indexBytes * 2;
            glNamedBufferData(indices_.get(), GLsizeiptr(indexBytes_), nullptr, GL_STREAM_DRAW);
        }
        glNamedBufferSubData(vertices_.get(), 0, GLsizeiptr(vertexBytes), list->VtxBuffer.Data);
        glNamedBufferSubData(indices_.get(), 0, GLsizeiptr(indexBytes), list->IdxBuffer.Data);
        for (int c = 0; c < list->CmdBuffer.Size; ++c) {
            const ImDrawCmd& cmd = list->CmdBuffer[c];
            if (cmd.UserCallback) {
                if (cmd.UserCallback != ImDrawCallback_ResetRenderState) cmd.UserCallback(list, &cmd);
                continue;
            }
            const float x0 = (cmd.ClipRect.x - offset.x) * scale.x, y0 = (cmd.ClipRect.y - offset.y) * scale.y;
            const float x1 = (cmd.ClipRect.z - offset.x) * scale.x, y1 = (cmd.ClipRect.w - offset.y) * scale.y;
            if (x1 <= x0 || y1 <= y0) continue;
            glScissor(int(x0), int(float(height) - y1), int(x1 - x0), int(y1 - y0));
            glBindTextureUnit(0, GLuint(reinterpret_cast<intptr_t>(cmd.TextureId)));
            glDrawElementsBaseVertex(GL_TRIANGLES, GLsizei(cmd.ElemCount),
                                     sizeof(ImDrawIdx) == 2 ? GL_UNSIGNED_SHORT : GL_UNSIGNED_INT,
                                     reinterpret_cast<void*>(size_t(cmd.IdxOffset) * sizeof(ImDrawIdx)), GLint(cmd.VtxOffset));
        }
    }
    glDisable(GL_SCISSOR_TEST);
    glDisable(GL_BLEND);
    glBindVertexArray(0);
}

} // namespace shadowlab
