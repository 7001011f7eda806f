// Reading GPU counters back without stalling the frame loop: each frame copies a small buffer
// into the next slot of a ring (a GPU-side copy) and sets a fence; the CPU reads only slots whose
// fence has already signalled (glClientWaitSync with a zero timeout never waits), newest first, so
// the values arrive one to kSlots frames late. The pattern csm's depth bounds and raytraced's
// counters follow with timer queries; this one is generic over the copied range.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <glad/gl.h>
#include <shadowlab/kit/handles.h>

namespace shadowlab::kit {

class ReadbackRing {
public:
    static constexpr int kSlots = 3;

    void create(IHost& host, size_t bytes, const char* label) {
        bytes_ = bytes;
        for (Slot& slot : ring_) {
            slot.buffer = Buffer(host, host.createBuffer(bytes, nullptr, GL_DYNAMIC_STORAGE_BIT, label));
            slot.fence = nullptr;
        }
        latest_.assign(bytes / sizeof(uint32_t), 0u);
    }
    // Fences are not host-tracked objects: released here (shutdown()).
    void destroy() {
        for (Slot& slot : ring_)
            if (slot.fence) glDeleteSync(std::exchange(slot.fence, nullptr));
    }

    // Copies `bytes` of `source` from `offset` into the next slot (after the writes that produced
    // them: the caller puts the barrier before).
    void push(GLuint source, size_t offset) {
        Slot& slot = ring_[size_t(next_)];
        if (slot.fence) glDeleteSync(slot.fence);
        glCopyNamedBufferSubData(source, slot.buffer, GLintptr(offset), 0, GLsizeiptr(bytes_));
        slot.fence = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
        slot.serial = ++serial_;
        next_ = (next_ + 1) % kSlots;
    }

    // Reads the newest finished slot, if any is newer than the last read; true when it did.
    bool poll() {
        Slot* newest = nullptr;
        for (Slot& slot : ring_) {
            if (!slot.fence || slot.serial <= readSerial_) continue;
            const GLenum state = glClientWaitSync(slot.fence, 0, 0);
            if (state != GL_ALREADY_SIGNALED && state != GL_CONDITION_SATISFIED) continue;
            if (!newest || slot.serial > newest->serial) newest = &slot;
        }
        if (!newest) return false;
        glGetNamedBufferSubData(newest->buffer, 0, GLsizeiptr(bytes_), latest_.data());
        readSerial_ = newest->serial;
        return true;
    }
    // The words of the last slot read (zeros before the first).
    const std::vector<uint32_t>& latest() const { return latest_; }

private:
    struct Slot {
        Buffer buffer;
        GLsync fence = nullptr;
        uint64_t serial = 0;
    };
    std::array<Slot, kSlots> ring_;
    std::vector<uint32_t> latest_;
    size_t bytes_ = 0;
    int next_ = 0;
    uint64_t serial_ = 0;
    uint64_t readSerial_ = 0;
};

} // namespace shadowlab::kit
