#pragma once
// A 2D image stack: frames of one size, each grey (rescaled values) or 8-bit RGB,
// with where each frame lies in the patient when the source says so, and the
// timing of a cine. What is not a volume opens as one: colour secondary captures
// (the dose report), palette colour, localizers, lone images, multi-frame
// ultrasound or XA cine (core/dicom/StackLoader.h loads them).

#include <cstdint>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "core/volume/SeriesInfo.h"

namespace lucent {

enum class StackColour { Grey, Rgb8 };

// One frame's place in the patient (LPS mm) and its time in a cine.
struct StackFrame {
    bool hasPosition = false;         // ImagePositionPatient/Orientation known
    glm::dvec3 position{0.0};         // centre of the first pixel
    glm::dvec3 rowDir{1.0, 0.0, 0.0}; // direction of increasing column index
    glm::dvec3 colDir{0.0, 1.0, 0.0}; // direction of increasing row index
    bool hasPixelSpacing = false;
    glm::dvec2 pixelSpacing{1.0}; // x: between columns, y: between rows (mm)
    double timeMs = 0.0;          // from the first frame (cine); 0 when unknown
};

// A grey window: values centre - width/2 .. centre + width/2 map to black .. white.
struct GreyWindow {
    double centre = 0.0;
    double width = 0.0;
    bool valid() const { return width > 0.0; }
};

struct ImageStack : SeriesInfo {
    int columns = 0;
    int rows = 0;
    StackColour colour = StackColour::Grey;
    std::vector<StackFrame> frames;
    // Grey: columns * rows values a frame, frame after frame, rescaled (HU for CT).
    std::vector<float> grey;
    // Rgb8: columns * rows * 3 bytes a frame (R, G, B), frame after frame.
    std::vector<std::uint8_t> rgb;

    GreyWindow window;        // from the header (its first window), else invalid
    bool inverted = false;    // MONOCHROME1: low values are shown white
    double frameTimeMs = 0.0; // nominal time between frames; 0 when not a timed cine
    std::string photometric;  // as stored: RGB, YBR_FULL_422, PALETTE COLOR, MONOCHROME1...
    std::vector<std::string> warnings;

    int frameCount() const { return static_cast<int>(frames.size()); }
    std::size_t pixelCount() const {
        return static_cast<std::size_t>(columns) * static_cast<std::size_t>(rows);
    }
    // One frame's values; frame must be in [0, frameCount()).
    std::span<const float> greyFrame(int frame) const;
    std::span<const std::uint8_t> rgbFrame(int frame) const;
    // The smallest and largest grey value of every frame ({0, 0} for colour).
    std::pair<double, double> greyRange() const;
    // The header's window, else one over the values' range.
    GreyWindow defaultWindow() const;
    // Time from one frame to the next for cine playback (frameTimeMs, else 10 fps).
    double cineIntervalMs() const { return frameTimeMs > 0.0 ? frameTimeMs : 100.0; }
};

// "2D stack, 6 frames, RGB" (for lists and the command line).
std::string describeStack(int frames, const std::string& photometric, int samplesPerPixel);

} // namespace lucent
