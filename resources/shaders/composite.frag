#version 430 core
// The ray caster's frame on the screen, with no read back (drawInPlace).
// Composite: the premultiplied frame over the background, texel for texel,
// as the read back composites it (rgb + (1 - alpha) * background, clamped).
// Stretch: a frame smaller than the target (an interactive one), composited
// first into 8 bits, stretched by the sampler's bilinear filter, as
// scaledTo() stretched the read back image: pixel centres aligned, edges
// clamped.

layout(location = 0) out vec4 outColour;

// One program each (the renderer prepends the #define): on llvmpipe a branch
// costs both of its sides.
const bool kStretch = LUCENT_STRETCH;
uniform sampler2D uFrame; // composite: premultiplied rgb, alpha (RGBA32F)
uniform sampler2D uShown; // stretch: the composited frame (RGBA8, linear)
uniform ivec2 uOrigin;    // the rectangle drawn, in the framebuffer (row 0 at the bottom)
uniform ivec2 uSize;
uniform vec3 uBackground;

void main() {
    if (kStretch) {
        vec2 at = (gl_FragCoord.xy - vec2(uOrigin)) / vec2(uSize);
        outColour = vec4(textureLod(uShown, at, 0.0).rgb, 1.0);
    } else {
        vec4 c = texelFetch(uFrame, ivec2(gl_FragCoord.xy) - uOrigin, 0);
        outColour = vec4(clamp(c.rgb + (1.0 - c.a) * uBackground, 0.0, 1.0), 1.0);
    }
}
