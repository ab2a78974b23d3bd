#version 450
#extension GL_GOOGLE_include_directive : require
// The compute rasteriser's small pass (shaders/raster_common.glsl), one invocation per
// triangle: a triangle with at most GLINT_RASTER_SMALL_PIXELS pixel centres in its box is
// covered here (most of a dense mesh's: 1-8 at 1M triangles and 1024²), any other goes to the
// large list for raster_large.comp.
#include "raster_common.glsl"

layout(local_size_x = GLINT_RASTER_GROUP) in;

void main() {
    const uint t = gl_GlobalInvocationID.x;
    if (t >= R.size.z) return;
    raster(t, false, 0u, 1u);
}
