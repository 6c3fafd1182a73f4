#include "ui/segmentation/SegmentSurfaces3d.h"

#include <stdexcept>

#include "core/formats/MeshFiles.h"
#include "core/segmentation/Segmentation.h"
#include "ui/volume/VolumeView.h"

namespace lucent {

SegmentSurfaces3d::SegmentSurfaces3d(VolumeView* view, const Segmentation* segmentation)
    : view_(view), segmentation_(segmentation) {}

const SurfaceResult& SegmentSurfaces3d::surfaceOf(std::uint32_t id) {
    const Segment* segment = segmentation_->find(id);
    if (!segment) {
        throw std::runtime_error("no segment " + std::to_string(id));
    }
    // Computed again only when the segments changed since (any edit, undo or redo).
    if (computedFor_ != id || computedRevision_ != segmentation_->revision()) {
        const SegmentMask empty(segmentation_->geometry().dims);
        computed_ = segmentSurface(segment->mask ? *segment->mask : empty,
                                   segmentation_->geometry(), options_, segment->name);
        computedFor_ = id;
        computedRevision_ = segmentation_->revision();
    }
    return computed_;
}

const SurfaceResult& SegmentSurfaces3d::show(std::uint32_t id, bool withVolume) {
    const SurfaceResult& surface = surfaceOf(id);
    const Segment* segment = segmentation_->find(id);
    auto display = std::make_shared<SurfaceDisplay>();
    display->mesh = std::make_shared<const TriangleMesh>(surface.mesh);
    display->colour =
        glm::dvec3(segment->colour[0], segment->colour[1], segment->colour[2]) / 255.0;
    display->showVolume = withVolume;
    view_->setSurfaceDisplay(std::move(display), 0.0);
    shown_ = id;
    return surface;
}

void SegmentSurfaces3d::hide() {
    if (shown_ != 0) {
        view_->setSurfaceDisplay(nullptr, 0.0);
        shown_ = 0;
    }
}

void SegmentSurfaces3d::exportSurface(std::uint32_t id, const std::filesystem::path& file) {
    const MeshFormat format = meshFormatOf(file);
    const SurfaceResult& surface = surfaceOf(id);
    MeshFileContent content;
    content.description = "Lucent segment " + segmentation_->find(id)->name;
    writeMesh(surface.mesh, file, format, content);
}

} // namespace lucent
