// Reading textures back to the CPU, two ways behind one interface:
//   ImmediateReader      glGetTextureImage straight into the destination: the CPU waits for the
//                        GPU (headless commands: eval, bench, render).
//   PixelBufferReadback  the reads are queued into one pixel-pack buffer and a fence after them;
//                        the frame loop polls the fence in later frames (never waits), maps the
//                        buffer once it has signalled, and the copies to the destinations may
//                        then run on any thread before unmap() (the window's "Measure accuracy",
//                        issue 32). One buffer, grown when a readback needs more, never made or
//                        deleted per frame; released with the object (GL thread).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "gl/gl.h"

namespace shadowlab {

class TextureReader {
public:
    virtual ~TextureReader() = default;
    // `bytes` of level 0 of `texture` as `format`/`type` into `into`, which must stay valid (and
    // its vector unresized) until the data is there: on return for an immediate reader, else
    // after PixelBufferReadback::deliver().
    virtual void read(GLuint texture, GLenum format, GLenum type, size_t bytes, void* into) = 0;
    // Whether `into` holds the texels on return (a caller may then decide on what it read).
    virtual bool immediate() const = 0;
};

class ImmediateReader final : public TextureReader {
public:
    void read(GLuint texture, GLenum format, GLenum type, size_t bytes, void* into) override;
    bool immediate() const override { return true; }
};

class PixelBufferReadback final : public TextureReader {
public:
    PixelBufferReadback() = default;
    ~PixelBufferReadback();
    PixelBufferReadback(const PixelBufferReadback&) = delete;
    PixelBufferReadback& operator=(const PixelBufferReadback&) = delete;

    // GL thread. Starts a readback of at most `bytes` in all: the buffer grows if it is smaller.
    void begin(size_t bytes);
    // Queued at the next offset of the buffer (false from immediate()). Reads past begin()'s size
    // are dropped with an error in the log (the caller sized them wrongly).
    void read(GLuint texture, GLenum format, GLenum type, size_t bytes, void* into) override;
    bool immediate() const override { return false; }
    // After the last read: the fence, flushed so that it signals without a later wait.
    void end();
    // GL thread, once a frame: true once the GPU has written every read (a zero-timeout poll).
    bool ready();
    // GL thread, after ready(): maps the buffer for reading (the data is there: no wait).
    bool map();
    // Any thread, between map() and unmap(): copies every read to its destination.
    void deliver() const;
    // GL thread: unmaps, drops the fence and the list of reads (idempotent).
    void reset();
    bool mapped() const { return mapped_ != nullptr; }

private:
    struct Read {
        size_t offset;
        size_t bytes;
        void* into;
    };
    GlBuffer buffer_;
    size_t capacity_ = 0;
    size_t used_ = 0;
    std::vector<Read> reads_;
    GLsync fence_ = nullptr;
    const uint8_t* mapped_ = nullptr;
};

} // namespace shadowlab
