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

#endif
