// The base of a kit technique: GL entry points loaded through the host, the host kept at hand,
// no-op defaults for every call. A technique overrides setup() (create what it needs once;
// kit handles release themselves) and the per-frame calls it uses.
#pragma once

#include <string>

#include <glad/gl.h>
#include <shadowlab/technique.h>

namespace shadowlab::kit {

class TechniqueBase : public IShadowTechnique {
public:
    bool init(IHost& host, std::string& error) final {
        host_ = &host;
        if (!gladLoadGL(host.glLoader())) {
            error = "could not load OpenGL entry points";
            return false;
        }
        return setup(error);
    }

protected:
    virtual bool setup(std::string& error) {
        (void)error;
        return true;
    }
    IHost& host() const { return *host_; }

private:
    IHost* host_ = nullptr;
};

} // namespace shadowlab::kit
