// Constants shared by GLSL and C++ (STYLE.md §2): plain #defines valid in both languages.
#ifndef GLINT_SHADERS_BINDINGS_H
#define GLINT_SHADERS_BINDINGS_H

// Vertex input bindings of the normal pipeline: positions and normals in separate buffers,
// both tightly packed float3 (Mesh::positions / Mesh::normals layout).
#define GLINT_BINDING_POSITION 0
#define GLINT_BINDING_NORMAL 1

// Colour attachments of the normal pass.
#define GLINT_ATTACHMENT_NORMAL_DEPTH 0  // RGBA32F: unit normal xyz, linear depth in w
#define GLINT_ATTACHMENT_PRIMITIVE 1     // R32_UINT: gl_PrimitiveID

// Push constants: mat4 clip_from_world (64 bytes) + vec4 depth row (16 bytes). 80 bytes is
// below the 128 bytes every Vulkan device guarantees (maxPushConstantsSize).
#define GLINT_PUSH_CONSTANT_BYTES 80

// Clear value of the primitive attachment: no triangle (render/frame.h kNoPrimitive).
#define GLINT_NO_PRIMITIVE 0xFFFFFFFFu

// ---- The compute rasteriser (render/context.h Raster::Compute; render/detail/vk_raster.h). ----
// Descriptor set 0 of raster_triangles.comp, raster_large.comp and raster_attributes.comp.
#define GLINT_RASTER_BINDING_POSITIONS 0     // float[3·V]: the mesh's vertex buffer
#define GLINT_RASTER_BINDING_NORMALS 1       // float[3·V]
#define GLINT_RASTER_BINDING_INDICES 2       // uint[3·T]: its index buffer
#define GLINT_RASTER_BINDING_VISIBILITY 3    // uint64 per sub-sample: depth bits << 32 | triangle
#define GLINT_RASTER_BINDING_LARGE 4         // uint: indirect dispatch (3), then large triangles
#define GLINT_RASTER_BINDING_NORMAL_DEPTH 5  // storage image rgba32f: the pass's colour target
#define GLINT_RASTER_BINDING_PRIMITIVE 6     // storage image r32ui
#define GLINT_RASTER_BINDING_COUNT 7

// Push constants of the three passes: mat4 clip_from_world (64 bytes), vec4 depth row (16),
// uvec4 (width, height, triangle count, GLINT_RASTER_CULL) (16).
#define GLINT_RASTER_PUSH_CONSTANT_BYTES 96
#define GLINT_RASTER_CULL 1u

// Workgroups: raster_triangles.comp one triangle per invocation; a triangle whose pixel
// bounding box holds more than GLINT_RASTER_SMALL_PIXELS pixel centres goes to the large list,
// which raster_large.comp covers with GLINT_RASTER_LARGE_SPLIT workgroups of
// GLINT_RASTER_LARGE_GROUP invocations per triangle; raster_attributes.comp
// GLINT_RASTER_TILE² sub-samples per workgroup. note: with 32 pixel centres, the test
// phantoms' triangles of 30-200 sub-samples went to the large pass, whose 1024 invocations per
// triangle made a sweep on lavapipe 5× slower (25 s against 4.6 s at 256).
#define GLINT_RASTER_GROUP 64
#define GLINT_RASTER_SMALL_PIXELS 256
#define GLINT_RASTER_LARGE_GROUP 256
#define GLINT_RASTER_LARGE_SPLIT 4
#define GLINT_RASTER_TILE 16
// Fixed-point sub-pixel bits of the vertex positions (Vulkan's subPixelPrecisionBits: 8 on
// lavapipe and NVIDIA) and the guard band: vertices beyond ±GLINT_RASTER_GUARD·w in x or y are
// clipped, which keeps fixed-point coordinates under 2^26 and edge functions in int64.
#define GLINT_RASTER_SUBPIXEL_BITS 8
#define GLINT_RASTER_GUARD 16.0

// ---- The GPU atlas (render/gpu_atlas.h): compare and back-project on the device. ----------
// Descriptor set 0 of both compute passes (atlas_pixels.comp, atlas_vertices.comp).
#define GLINT_ATLAS_BINDING_PARAMS 0             // uniform: the view (AtlasParams)
#define GLINT_ATLAS_BINDING_REF_NORMAL_DEPTH 1   // storage image rgba32f: reference sub-samples
#define GLINT_ATLAS_BINDING_REF_PRIMITIVE 2      // storage image r32ui
#define GLINT_ATLAS_BINDING_EXA_NORMAL_DEPTH 3   // storage image rgba32f: examined sub-samples
#define GLINT_ATLAS_BINDING_EXA_PRIMITIVE 4      // storage image r32ui
#define GLINT_ATLAS_BINDING_POSITIONS 5          // float[3·V]: the reference renderer's vertex buffer
#define GLINT_ATLAS_BINDING_NORMALS 6            // float[3·V]
#define GLINT_ATLAS_BINDING_INDICES 7            // uint[3·T]: its index buffer
#define GLINT_ATLAS_BINDING_SUMS 8               // int64 [zoom][GLINT_SUM_*][vertex], fixed point
#define GLINT_ATLAS_BINDING_WORDS 9              // uint [zoom][GLINT_WORD_*][vertex]
#define GLINT_ATLAS_BINDING_SCRATCH_KEY 10       // uint64 [vertex]: this view's maximum (value, pixel)
#define GLINT_ATLAS_BINDING_SCRATCH_COS 11       // uint [vertex]: this view's best incidence
#define GLINT_ATLAS_BINDING_PIXELS 12            // PixelDeviation [pixel]: this view's comparison
#define GLINT_ATLAS_BINDING_SUMMARY 13           // ViewTotals: this view's numbers
#define GLINT_ATLAS_BINDING_COUNT 14

// Workgroups: the pixel pass runs GLINT_ATLAS_TILE² invocations, the vertex pass
// GLINT_ATLAS_VERTEX_GROUP.
#define GLINT_ATLAS_TILE 16
#define GLINT_ATLAS_VERTEX_GROUP 256

// Per-vertex fixed-point sums (int64, scaled by AtlasParams.scales) and 32-bit fields.
#define GLINT_SUM_WEIGHT 0
#define GLINT_SUM_VALUE 1
#define GLINT_SUM_MISSING 2
#define GLINT_SUM_DEPTH 3
#define GLINT_SUM_FIELDS 4
#define GLINT_WORD_COUNT 0         // observations (uint)
#define GLINT_WORD_MAX 1           // float bits of the maximum value
#define GLINT_WORD_DEPTH_AT_MAX 2  // float bits of the signed depth at the maximum (NaN: none)
#define GLINT_WORD_MAX_VIEW 3      // int: view of the maximum (-1: none)
#define GLINT_WORD_BEST_COS 4      // float bits of the most frontal incidence (-2: none)
#define GLINT_WORD_BEST_VIEW 5     // int: its view (-1: none)
#define GLINT_WORD_FIELDS 6

// PixelDeviation.flags: the silhouette code (0 same, 1 reference only, 2 examined only, as
// scanner/compare.h), whether the reference pixel is covered, whether both were compared.
#define GLINT_PIXEL_SILHOUETTE_MASK 3u
#define GLINT_PIXEL_REFERENCE_ONLY 1u
#define GLINT_PIXEL_EXAMINED_ONLY 2u
#define GLINT_PIXEL_REFERENCE_COVERED 4u
#define GLINT_PIXEL_COMPARED 8u

// AtlasParams.mode.x
#define GLINT_ATLAS_PERSPECTIVE 1u
#define GLINT_ATLAS_METRIC_RGB 2u

#endif
