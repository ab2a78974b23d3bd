#version 450
#extension GL_GOOGLE_include_directive : require
// The compute rasteriser's small pass (shaders/raster_common.glsl), one invocation per
// triangle: a triangle with at most GLINT_RASTER_SMALL_PIXELS pixel centres in its box is
// covered here (a dense mesh's all: 1-8 at 1M triangles and 1024²), any other goes to the
// large list for raster_large.comp.
#include "raster_common.glsl"

layout(local_size_x = GLINT_RASTER_GROUP) in;

void main() {
    // Grid-stride: a mesh with more triangles than one dispatch's workgroups reach
    // (maxComputeWorkGroupCount[0] · GLINT_RASTER_GROUP: 4.2M at the 65535 Vulkan guarantees).
    const uint step = gl_NumWorkGroups.x * GLINT_RASTER_GROUP;
    for (uint t = gl_GlobalInvocationID.x; t < R.size.z; t += step) raster(t, false, 0u, 1u);
}
