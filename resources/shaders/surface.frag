#version 430 core
// The surface lit by a headlight (Blinn-Phong with the light at the eye: the
// half vector is the view direction), two-sided, with the volume's shading
// parameters; and the eye distance along the pixel's ray, at which the ray
// caster stops that pixel's ray (raycast.frag, kSurface).

layout(location = 0) out vec4 outColour;    // premultiplied: opaque
layout(location = 1) out float outDistance; // mm from the eye: the rays' parameter t

in vec3 vFromEye;
in vec3 vNormal;
in float vField;

uniform vec4 uLight; // ambient, diffuse, specular, specular power
uniform bool uUseField;
uniform vec3 uColour;                  // plain
uniform float uFieldLo, uFieldScale;   // t = (field - lo) * scale + offset
uniform float uFieldOffset;
uniform sampler1D uColourMap;          // viridis, linear between its entries
uniform int uColourMapSize;

void main() {
    // Interpolated with perspective at the pixel's centre: the point where the
    // pixel's ray meets the triangle.
    float t = length(vFromEye);
    vec3 w = vFromEye / t;
    vec3 n = vNormal;
    if (dot(n, n) < 1e-12) {
        n = cross(dFdx(vFromEye), dFdy(vFromEye)); // a vertex of no area: the face's normal
    }
    float len = length(n);
    float ndotl = len > 0.0 ? min(1.0, abs(dot(n, w)) / len) : 1.0;
    vec3 base = uColour;
    if (uUseField) {
        float f = clamp((vField - uFieldLo) * uFieldScale + uFieldOffset, 0.0, 1.0);
        float at = (f * float(uColourMapSize - 1) + 0.5) / float(uColourMapSize);
        base = texture(uColourMap, at).rgb;
    }
    float specular = ndotl > 0.0 ? uLight.z * pow(ndotl, uLight.w) : 0.0;
    vec3 lit = base * (uLight.x + uLight.y * ndotl) + vec3(specular);
    outColour = vec4(clamp(lit, 0.0, 1.0), 1.0);
    outDistance = t;
}
