#pragma once
// The shear-warp anchor of the CPU render benchmark (issue 31): VolPack 1.0b3
// (Lacroute & Levoy 1994; Debian's libvolpack1-dev) through its C API, on the
// scene Lucent's CPU caster renders: the same volume, transfer function and
// headlight Phong shading, the same image size and view direction.
//
// What VolPack cannot do the same way, and so differs from Lucent's image:
//  - Projection: VolPack 1.0 renders parallel projections only (vpWindow's
//    VP_PERSPECTIVE is "not supported"); the window is Lucent's view at the
//    volume's centre (half size = fit distance * tan(fov / 2)), so the front of
//    the volume is drawn smaller and the back larger than in Lucent's
//    perspective image.
//  - Sampling: one bilinear sample per slice along the principal axis
//    (shear-warp), pre-classified and pre-shaded voxels, opacities in 8 bits,
//    normals in VolPack's 13-bit code, then a 2D warp of the intermediate image.
//  - One thread (VolPack has no threads).
//  - Colour from 256 bins over the preset's colour ramp: VolPack's material
//    weights are indexed by a one-byte field (opacity keeps the full value).
// The shading table is filled here each frame rather than by vpShadeTable:
// vpShadeTable shades in object space through the model matrix, which holds the
// voxel spacing here (0.45 x 0.45 x 1 mm) and would skew every normal; the table
// below is Lucent's headlight model (ambient + diffuse |n.v|, white specular
// |n.v|^p, two-sided) on normals computed in millimetres.
#include <cstdint>
#include <memory>
#include <vector>

#include "core/image/Image.h"
#include "core/scene/Camera.h"
#include "core/tf/TransferFunction.h"
#include "core/volume/Volume.h"

// volpack.h's handle, declared as it declares it.
typedef struct _vp_context vpContext;

namespace lucent::bench {

class VolPackAnchor {
public:
    // Classifies `volume` once (as Lucent caches its classification): opacities
    // of `tf` (per voxel of the smallest spacing) rewritten per voxel along the
    // axis that `firstView` looks along, VolPack's unit. Throws
    // std::runtime_error naming the VolPack call that failed.
    VolPackAnchor(const Volume& volume, const TransferFunction& tf, const Camera& firstView,
                  int width, int height);
    ~VolPackAnchor();
    VolPackAnchor(const VolPackAnchor&) = delete;
    VolPackAnchor& operator=(const VolPackAnchor&) = delete;

    // One frame: view matrix, shading table, vpRenderClassifiedVolume (shear,
    // composite, warp). Top row first, over black, alpha 255.
    ImageRGBA8 render(const Camera& camera);

    // The volume axis VolPack composited along in the last frame (0 i, 1 j, 2 k),
    // and the one the opacities were classified for.
    int lastAxis() const;
    int classifiedAxis() const { return axis_; }

private:
    struct ContextDeleter {
        void operator()(vpContext* c) const;
    };
    void classify(const TransferFunction& tf);
    void fillShadeTable(const glm::dvec3& forward);

    // VolPack's voxel: the shading fields first (its rule), then the classification's.
    struct Voxel {
        std::uint16_t normal; // VolPack's normal code: the row of the colour table
        std::uint8_t colour;  // the value in 256 bins over the colour ramp: the weights' row
        std::uint8_t unused;
        std::uint16_t scalar; // value + offset: the opacity table's row
    };
    // The value whose colour bin b (0..255) holds.
    double binValue(int bin) const { return colourLo_ + (bin + 0.5) * colourStep_; }

    const Volume& volume_;
    Shading shading_;
    int width_, height_;
    int axis_ = 1;
    double scalarOffset_ = 0.0; // voxel value + offset = the scalar field (0 .. tableSize - 1)
    int tableSize_ = 0;
    double colourLo_ = 0.0, colourStep_ = 1.0; // the colour bins
    std::unique_ptr<vpContext, ContextDeleter> context_;
    std::vector<Voxel> voxels_;
    std::vector<float> opacityTable_; // per scalar
    std::vector<float> weightTable_;  // per colour bin: r, g, b, 1 (the four "materials")
    std::vector<float> colourTable_;  // per normal code: (shade, 0, 0), (0, shade, 0), ...
    std::vector<glm::dvec3> normals_; // per normal code, LPS unit vector
    std::vector<std::uint8_t> rgb_;   // VolPack's image, 3 bytes per pixel
};

} // namespace lucent::bench
