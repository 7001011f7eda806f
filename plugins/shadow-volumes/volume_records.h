// shadow-volumes, extract = compute: the volumes as records in GPU buffers instead of a geometry
// stage. volume_extract.comp, one invocation per caster triangle, writes the same sides and caps
// volume.geom emits (the same decisions and vertices) as records to storage buffers, counting them
// with atomics into three indirect draw commands, and volume_indirect.vert draws them with
// glDrawArraysIndirect (dormon/Shadows' CSSV approach). The buffers hold the worst case (a side per
// edge of a closed mesh, three sides a triangle of any other, a cap a triangle), allocated when the
// scene's casters change, never per frame; the CPU never reads the counts. The image is the
// geometry variant's (on llvmpipe but for single pixels where a volume face meets the visible
// surface, whose depth rounds differently after a geometry stage: docs/shadow-volumes.md).
#pragma once

#include <cstdint>
#include <string>

#include <shadowlab/kit/handles.h>
#include <shadowlab/technique.h>

namespace shadow_volumes {

class VolumeRecords {
public:
    // Once in setup(): the programs, a vertex array without attributes for the indirect draws and
    // the device's storage block limit.
    bool create(shadowlab::IHost& host, std::string& error);
    void destroy();

    // The host's casters with adjacency, with the record buffers sized for them; null (the
    // geometry stage draws instead, said once per scene) when the host lacks the extension or the
    // worst case does not fit a storage block.
    const shadowlab::AdjacencyScene* prepare();
    // extract = geometry: the buffers go (on the frame the parameter changes; a no-op after), so
    // the technique's memory is the variant's own.
    void release();

    // The sides and caps of every caster into the records and the draw counts.
    void extract(const shadowlab::AdjacencyScene& scene, float push);
    // This frame's records, drawn indirectly; `edges`: their edges as lines (the debug image);
    // `increment`: what each fragment adds to a debug image.
    void draw(float push, float increment, bool edges);

private:
    shadowlab::IHost* host_ = nullptr;
    shadowlab::kit::Program extract_, indirect_;
    // The records (capacities in records, 0 until allocated) and the commands.
    shadowlab::kit::Buffer sides_, caps_, commands_;
    uint32_t sideCapacity_ = 0, capCapacity_ = 0;
    GLuint emptyVao_ = 0;
    uint64_t maxBlockBytes_ = 0;
    bool warned_ = false;   // the fallback to geometry was said
};

} // namespace shadow_volumes
