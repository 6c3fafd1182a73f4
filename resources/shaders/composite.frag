#version 430 core
// The ray caster's premultiplied frame over the background, drawn straight
// into a framebuffer (the 3D view's): the same compositing as the read back
// (rgb + (1 - alpha) * background, clamped). A frame of the target's size is
// read texel for texel; a smaller (interactive) one is stretched bilinearly
// as scaledTo() stretched the read back image: pixel centres aligned, edges
// clamped, each texel composited and clamped before it is interpolated (a
// shaded highlight above 1 must not brighten its neighbours).

layout(location = 0) out vec4 outColour;

uniform sampler2D uFrame; // premultiplied rgb, alpha; row 0 at the bottom, as the target's
uniform ivec2 uOrigin;    // the target rectangle in the framebuffer
uniform ivec2 uSize;
uniform bool uSameSize;
uniform vec3 uBackground;

vec3 shown(ivec2 texel) {
    vec4 c = texelFetch(uFrame, texel, 0);
    return clamp(c.rgb + (1.0 - c.a) * uBackground, 0.0, 1.0);
}

void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy) - uOrigin;
    if (uSameSize) {
        outColour = vec4(shown(pixel), 1.0);
        return;
    }
    ivec2 frame = textureSize(uFrame, 0);
    vec2 f = clamp((vec2(pixel) + 0.5) * vec2(frame) / vec2(uSize) - 0.5, vec2(0.0),
                   vec2(frame - 1));
    ivec2 p0 = ivec2(f);
    ivec2 p1 = min(p0 + 1, frame - 1);
    vec2 w = f - vec2(p0);
    vec3 bottom = mix(shown(p0), shown(ivec2(p1.x, p0.y)), w.x);
    vec3 top = mix(shown(ivec2(p0.x, p1.y)), shown(p1), w.x);
    outColour = vec4(mix(bottom, top, w.y), 1.0);
}
