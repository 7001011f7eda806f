// shadow-volumes: bindings shared by the plugin's C++ and GLSL.
#ifndef SHADOW_VOLUMES_SHARED_H
#define SHADOW_VOLUMES_SHARED_H
#include "shadowlab/kit/shared.h"

SHADOWLAB_SHARED_BEGIN(shadow_volumes)
SHADOWLAB_TEXTURE_UNIT(kVolumeMaskUnit, 4)     // the volume count: the stencil of a D24S8 texture (screen space)
// Uniform locations and storage-buffer bindings are integer constants like a unit.
// The world distance the volumes start beyond each caster.
SHADOWLAB_TEXTURE_UNIT(kPushLocation, 16)
// volume_count.frag: what a fragment adds to a debug image.
SHADOWLAB_TEXTURE_UNIT(kIncrementLocation, 17)
// extract = compute (volume_extract.comp, volume_indirect.vert): the records' capacities (x sides,
// y caps), the batch (first object, objects in this dispatch, first triangle, triangles), its
// base vertex and closed flag, and what volume_indirect.vert draws (kDraw*).
SHADOWLAB_TEXTURE_UNIT(kCapacityLocation, 18)
SHADOWLAB_TEXTURE_UNIT(kBatchLocation, 19)
SHADOWLAB_TEXTURE_UNIT(kMeshLocation, 20)
SHADOWLAB_TEXTURE_UNIT(kDrawLocation, 21)
SHADOWLAB_TEXTURE_UNIT(kDrawSides, 0)
SHADOWLAB_TEXTURE_UNIT(kDrawNearCaps, 1)
SHADOWLAB_TEXTURE_UNIT(kDrawFarCaps, 2)
SHADOWLAB_TEXTURE_UNIT(kDrawEdges, 3)
// Storage buffers: the host's vertices and triangles with adjacency (SHADOWLAB_EXT_ADJACENCY), the
// records the extraction writes (sides: 6 floats, the edge's two world points in the side's
// orientation; caps: 9 floats, a triangle turned to face the light) and the indirect commands.
SHADOWLAB_TEXTURE_UNIT(kVerticesBinding, 2)
SHADOWLAB_TEXTURE_UNIT(kAdjacencyBinding, 3)
SHADOWLAB_TEXTURE_UNIT(kSidesBinding, 4)
SHADOWLAB_TEXTURE_UNIT(kCapsBinding, 5)
SHADOWLAB_TEXTURE_UNIT(kCommandsBinding, 6)
// The commands buffer: three DrawArraysIndirectCommand {count, instanceCount, first, baseInstance}
// (uints 0-3 the sides, 6 vertices each; 4-7 the near caps and 8-11 the far caps, 3 vertices each).
SHADOWLAB_TEXTURE_UNIT(kSideCommand, 0)
SHADOWLAB_TEXTURE_UNIT(kNearCapCommand, 4)
SHADOWLAB_TEXTURE_UNIT(kFarCapCommand, 8)
SHADOWLAB_TEXTURE_UNIT(kExtractGroupSize, 64)
SHADOWLAB_SHARED_END
#endif
