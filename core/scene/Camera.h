#pragma once

namespace lucent {

// The default view looks at the patient from the front (anterior), head up.
// azimuth turns about the head-foot axis, elevation about the left-right axis;
// zoom 1 fits the volume's bounding sphere in the view. Perspective projection.
// The camera looks at the volume's centre moved by (panRight, panUp) along the
// view's right and up axes, from `distance` mm away; distance 0 means the
// distance at which zoom 1 fits the volume. A distance shorter than the
// volume's radius puts the eye inside the volume (rays start at the eye).
struct Camera {
    double azimuth = 0.0;   // degrees
    double elevation = 0.0; // degrees
    double zoom = 1.0;
    double fieldOfView = 30.0; // degrees, vertical
    double distance = 0.0;     // mm; 0: fit the volume
    double panRight = 0.0;     // mm
    double panUp = 0.0;        // mm
};

} // namespace lucent
