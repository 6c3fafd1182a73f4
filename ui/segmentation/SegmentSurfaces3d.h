#pragma once
// A segment shown as a surface in the 3D view: its mesh (core/segmentation/SegmentSurface.h)
// in the segment's colour, through the view's surface display (core/scene/SurfaceDisplay.h,
// drawn by the GPU ray caster with the volume's rays stopped at it); and that surface written
// to STL, PLY or OBJ (core/formats/MeshFiles.h) for printing. The display holds one mesh: the
// segment shown last replaces the one before.

#include <cstdint>
#include <filesystem>
#include <memory>

#include "core/segmentation/SegmentSurface.h"

namespace lucent {

class Segmentation;
class VolumeView;

class SegmentSurfaces3d {
public:
    // The segmentation must outlive this object and lie on the grid of the view's volume.
    SegmentSurfaces3d(VolumeView* view, const Segmentation* segmentation);

    void setOptions(const SegmentSurfaceOptions& options) { options_ = options; }
    // Computes the segment's surface and shows it (with the volume when withVolume).
    // std::runtime_error for an unknown or empty segment (the message names it).
    const SurfaceResult& show(std::uint32_t segment, bool withVolume = true);
    void hide();
    std::uint32_t shown() const { return shown_; } // 0: none

    // Writes the segment's surface (the one shown when it is that segment's, computed
    // otherwise) as the file's extension says; std::invalid_argument for an unknown
    // extension, std::runtime_error naming the file when it cannot be written.
    void exportSurface(std::uint32_t segment, const std::filesystem::path& file);

private:
    const SurfaceResult& surfaceOf(std::uint32_t segment);

    VolumeView* view_;
    const Segmentation* segmentation_;
    SegmentSurfaceOptions options_;
    std::uint32_t shown_ = 0;
    std::uint32_t computedFor_ = 0;
    std::uint64_t computedRevision_ = 0;
    SurfaceResult computed_;
};

} // namespace lucent
