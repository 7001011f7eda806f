// RAII handles for what a technique creates through IHost: released through the host when they
// go (or are reassigned), so a technique never writes a destroy call by hand. Move-only.
#pragma once

#include <cstring>
#include <type_traits>
#include <utility>

#include <glad/gl.h>
#include <shadowlab/technique.h>

namespace shadowlab::kit {

namespace detail {
template <void (IHost::*Destroy)(uint32_t)>
class HostHandle {
public:
    HostHandle() = default;
    HostHandle(IHost& host, uint32_t name) : host_(&host), name_(name) {}
    HostHandle(HostHandle&& other) noexcept : host_(other.host_), name_(std::exchange(other.name_, 0u)) {}
    HostHandle& operator=(HostHandle&& other) noexcept {
        if (this != &other) {
            reset();
            host_ = other.host_;
            name_ = std::exchange(other.name_, 0u);
        }
        return *this;
    }
    HostHandle(const HostHandle&) = delete;
    HostHandle& operator=(const HostHandle&) = delete;
    ~HostHandle() { reset(); }

    void reset() {
        if (name_ && host_) (host_->*Destroy)(name_);
        name_ = 0;
    }
    uint32_t get() const { return name_; }
    operator uint32_t() const { return name_; }
    explicit operator bool() const { return name_ != 0; }

private:
    IHost* host_ = nullptr;
    uint32_t name_ = 0;
};
} // namespace detail

using Texture = detail::HostHandle<&IHost::destroyTexture>;
using Buffer = detail::HostHandle<&IHost::destroyBuffer>;
using Framebuffer = detail::HostHandle<&IHost::destroyFramebuffer>;

// A program built by the host from files (hot-reloaded: use get() every frame, never cache it).
class Program {
public:
    Program() = default;
    Program(Program&& other) noexcept : host_(other.host_), id_(std::exchange(other.id_, 0u)) {}
    Program& operator=(Program&& other) noexcept {
        if (this != &other) {
            reset();
            host_ = other.host_;
            id_ = std::exchange(other.id_, 0u);
        }
        return *this;
    }
    Program(const Program&) = delete;
    Program& operator=(const Program&) = delete;
    ~Program() { reset(); }

    bool build(IHost& host, const ProgramDesc& desc, std::string& error) {
        reset();
        host_ = &host;
        id_ = host.buildProgram(desc, error);
        return id_ != 0;
    }
    // Binds the program and returns its GL name.
    uint32_t use() const {
        const uint32_t program = get();
        glUseProgram(program);
        return program;
    }
    uint32_t get() const { return host_ && id_ ? host_->glProgram(id_) : 0u; }
    void reset() {
        if (id_ && host_) host_->destroyProgram(id_);
        id_ = 0;
    }

private:
    IHost* host_ = nullptr;
    ProgramId id_ = 0;
};

inline Texture makeTexture(IHost& host, const TextureDesc& desc) { return Texture(host, host.createTexture(desc)); }
inline Framebuffer makeFramebuffer(IHost& host, const char* label) {
    return Framebuffer(host, host.createFramebuffer(label));
}

// A uniform block declared with SHADOWLAB_UNIFORM_BLOCK (shared.h): one buffer, written with
// update() (a small glNamedBufferSubData: no stall) and bound to the block's binding point.
template <class Block>
class UniformBlock {
    static_assert(std::is_standard_layout_v<Block> && std::is_trivially_copyable_v<Block>);
    static_assert(sizeof(Block) % 16 == 0, "std140 blocks are a multiple of 16 bytes");

public:
    void create(IHost& host, const char* label) {
        buffer_ = Buffer(host, host.createBuffer(sizeof(Block), nullptr, GL_DYNAMIC_STORAGE_BIT, label));
    }
    void update(const Block& values) {
        if (std::memcmp(&values, &last_, sizeof(Block)) == 0 && written_) return;
        glNamedBufferSubData(buffer_, 0, sizeof(Block), &values);
        last_ = values;
        written_ = true;
    }
    void bind() const { glBindBufferBase(GL_UNIFORM_BUFFER, Block::kBinding, buffer_); }
    // update() then bind(): what a main pass usually wants.
    void set(const Block& values) {
        update(values);
        bind();
    }

private:
    Buffer buffer_;
    Block last_{};
    bool written_ = false;
};

} // namespace shadowlab::kit
