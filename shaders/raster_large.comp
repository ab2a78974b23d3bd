#version 450
#extension GL_GOOGLE_include_directive : require
// The compute rasteriser's large pass (shaders/raster_common.glsl): the triangles the small
// pass listed (large boxes, clipping), each covered by GLINT_RASTER_LARGE_SPLIT workgroups
// that share its box's pixel centres; the workgroups along x walk the list.
#include "raster_common.glsl"

layout(local_size_x = GLINT_RASTER_LARGE_GROUP) in;

void main() {
    const uint stride = GLINT_RASTER_LARGE_GROUP * GLINT_RASTER_LARGE_SPLIT;
    const uint first = gl_WorkGroupID.y * GLINT_RASTER_LARGE_GROUP + gl_LocalInvocationID.x;
    for (uint i = gl_WorkGroupID.x; i < large_count; i += gl_NumWorkGroups.x)
        raster(large[i], true, first, stride);
}
