#version 430 core
// A surface shown with the volume (render/SurfaceRenderer): positions relative
// to the mesh's centre, so that floats keep them to a micrometre; the eye and
// the view are the ray caster's (core/scene/ViewFrame.h), so that each pixel's
// centre lies on that pixel's ray.

layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec3 inNormal;
layout(location = 2) in float inField;

uniform vec3 uEye;        // relative to the mesh's centre, mm
uniform mat3 uView;       // rows: right, up, -forward
uniform vec4 uProjection; // x scale, y scale, depth scale, depth offset

out vec3 vFromEye; // mm
out vec3 vNormal;
out float vField;

void main() {
    vFromEye = inPosition - uEye;
    vNormal = inNormal;
    vField = inField;
    vec3 v = uView * vFromEye;
    gl_Position = vec4(v.x * uProjection.x, v.y * uProjection.y, v.z * uProjection.z + uProjection.w,
                       -v.z);
}
