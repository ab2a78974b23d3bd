#version 450
#extension GL_GOOGLE_include_directive : require
// Normal pass, fragment stage: the interpolated vertex normal, normalised (the paper's
// normal colour before the 0.5·n + 0.5 mapping, kept as float), the linear depth and the
// triangle index (gl_PrimitiveID: needs the geometryShader feature).
#include "bindings.h"

layout(location = 0) in vec3 in_normal;
layout(location = 1) in float in_depth;

layout(location = GLINT_ATTACHMENT_NORMAL_DEPTH) out vec4 out_normal_depth;
layout(location = GLINT_ATTACHMENT_PRIMITIVE) out uint out_primitive;

void main() {
    // note: a zero interpolated normal (opposite vertex normals across a fold) stays zero;
    // normalize() of it would be NaN.
    const float len = length(in_normal);
    out_normal_depth = vec4(len > 0.0 ? in_normal / len : vec3(0.0), in_depth);
    out_primitive = uint(gl_PrimitiveID);
}
