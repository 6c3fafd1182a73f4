#version 430 core
// One triangle that covers the viewport (the target rectangle): the frame
// drawn in place, one fragment a pixel of the target.
void main() {
    const vec2 p = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2);
    gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
}
