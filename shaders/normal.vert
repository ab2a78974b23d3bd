#version 450
#extension GL_GOOGLE_include_directive : require
// Normal pass, vertex stage: world position -> clip space; passes the world normal and the
// linear depth along the viewing axis (a linear function of position, so perspective-correct
// interpolation reproduces it exactly at every fragment).
#include "bindings.h"

layout(location = GLINT_BINDING_POSITION) in vec3 in_position;
layout(location = GLINT_BINDING_NORMAL) in vec3 in_normal;

layout(push_constant) uniform PushConstants {
    mat4 clip_from_world;
    // depth = dot(depth_row.xyz, p) + depth_row.w: the camera's -z row of camera_from_world.
    vec4 depth_row;
} pc;

layout(location = 0) out vec3 out_normal;
layout(location = 1) out float out_depth;

void main() {
    gl_Position = pc.clip_from_world * vec4(in_position, 1.0);
    out_normal = in_normal;
    out_depth = dot(pc.depth_row.xyz, in_position) + pc.depth_row.w;
}
