#include "core/movie/MovieFrames.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "core/movie/MovieWriter.h"
#include "core/scene/Renderer.h"
#include "core/scene/Turntable.h"

namespace lucent {

RenderDescription turntableFrame(const RenderDescription& start, double degrees, int frames,
                                 int k) {
    RenderDescription d = start;
    d.camera = turntableCamera(start.camera, degrees, frames, k);
    return d;
}

TurntableFrames::TurntableFrames(Renderer& renderer, const RenderDescription& start, double degrees,
                                 int frames)
    : renderer_(renderer), start_(start), degrees_(degrees), frames_(frames) {
    if (frames < 1) {
        throw std::invalid_argument("a turntable needs at least one frame");
    }
    if (!std::isfinite(degrees)) {
        throw std::invalid_argument("turntable degrees must be a finite number");
    }
}

ImageRGBA8 TurntableFrames::frame(int k) {
    return renderer_.render(turntableFrame(start_, degrees_, frames_, k)).image;
}

IndexAxis parseIndexAxis(std::string_view text) {
    if (text == "i") {
        return IndexAxis::I;
    }
    if (text == "j") {
        return IndexAxis::J;
    }
    if (text == "k") {
        return IndexAxis::K;
    }
    throw std::invalid_argument("axis '" + std::string(text) + "' is not i, j or k");
}

int sliceCount(const VolumeGeometry& geometry, IndexAxis axis) {
    return geometry.dims[int(axis)];
}

int cineSlice(int slices, int frames, int k) {
    if (frames <= 0 || frames >= slices) {
        return std::clamp(k, 0, std::max(slices - 1, 0));
    }
    if (frames == 1) {
        return slices / 2;
    }
    return int(std::lround(double(k) * double(slices - 1) / double(frames - 1)));
}

SlicePlane cinePlane(const VolumeGeometry& geometry, IndexAxis axis, int slice, int width,
                     int height) {
    const int a = int(axis);
    const glm::dvec3 normal = geometry.direction[a];
    // The radiological view nearest the slice: axial, coronal or sagittal.
    const glm::dvec3 along = glm::abs(normal);
    const Orientation nearest = along.z >= along.x && along.z >= along.y ? Orientation::Axial
                                : along.y >= along.x                     ? Orientation::Coronal
                                                                         : Orientation::Sagittal;
    glm::dvec3 centre = (glm::dvec3(geometry.dims) - 1.0) * 0.5;
    centre[a] = slice;
    SlicePlane plane = standardPlane(geometry, nearest, geometry.toPatient(centre));
    // The other two index axes, the one nearer the view's right axis as u.
    glm::dvec3 first = geometry.direction[(a + 1) % 3];
    glm::dvec3 second = geometry.direction[(a + 2) % 3];
    if (std::abs(glm::dot(second, plane.u)) > std::abs(glm::dot(first, plane.u))) {
        std::swap(first, second);
    }
    const glm::dvec3 u = glm::dot(first, plane.u) < 0.0 ? -first : first;
    const glm::dvec3 v = glm::dot(second, plane.v) < 0.0 ? -second : second;
    plane.u = u;
    plane.v = v;
    plane.width = std::max(0, width);
    plane.height = std::max(0, height);
    plane.pixelSize = fitPixelSize(geometry, u, v, plane.width, plane.height);
    return plane;
}

ImageRGBA8 windowedSlice(const Volume& volume, const SlicePlane& plane, const WindowLevel& window) {
    const std::vector<float> samples = sampleImage(volume, plane);
    ImageRGBA8 image = ImageRGBA8::filled(plane.width, plane.height, 255);
    for (std::size_t n = 0; n < samples.size(); ++n) {
        const std::uint8_t grey = windowToGrey(samples[n], window.center, window.width);
        std::fill_n(image.pixels.begin() + std::ptrdiff_t(4 * n), 3, grey);
    }
    return image;
}

CineFrames::CineFrames(const Volume& volume, IndexAxis axis, int frames, const WindowLevel& window,
                       int width, int height)
    : volume_(volume), axis_(axis), slices_(sliceCount(volume.geometry(), axis)),
      frames_(frames > 0 ? std::min(frames, slices_) : slices_), window_(window), width_(width),
      height_(height) {
    if (volume.empty()) {
        throw std::invalid_argument("a cine needs a volume");
    }
    if (frames < 0) {
        throw std::invalid_argument("a cine needs a positive number of frames (0: every slice)");
    }
}

ImageRGBA8 CineFrames::frame(int k) {
    const SlicePlane plane =
        cinePlane(volume_.geometry(), axis_, cineSlice(slices_, frames_, k), width_, height_);
    return windowedSlice(volume_, plane, window_);
}

bool writeMovie(MovieFrames& frames, MovieWriter& writer,
                const std::function<bool(int, int)>& progress) {
    const int total = frames.count();
    if (progress && !progress(0, total)) {
        return false;
    }
    for (int k = 0; k < total; ++k) {
        writer.add(frames.frame(k));
        if (progress && !progress(k + 1, total)) {
            return false;
        }
    }
    writer.finish();
    return true;
}

} // namespace lucent
