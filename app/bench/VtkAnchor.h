#pragma once
// VTK 9.1, the anchor of the render benchmarks (issue 31), run in the same
// benchmark as Lucent: app/bench/vtk_anchor.py (carried in the binary) under
// xvfb-run (Debian's python3-vtk9, Mesa llvmpipe through GLX), on a MetaImage
// written by lucent-cli convert's writer and the preset written by
// writeTransferFunction. Mapper "fixed": vtkFixedPointVolumeRayCastMapper
// (2 threads), the CPU caster's anchor; "gpu": vtkGPUVolumeRayCastMapper, the
// GL caster's. Both render Lucent's scene (BenchScenes.h): the preset, shading,
// trilinear, step 0.5 voxel of the smallest spacing, Lucent's anterior camera,
// 6 frames turning 5 degrees.
#include <filesystem>
#include <memory>
#include <string>

#include "core/image/Image.h"
#include "core/tf/TransferFunction.h"
#include "core/volume/Volume.h"

class QTemporaryDir;

namespace lucent::bench {

struct VtkAnchorRun {
    double renderMs = 0.0;  // median of the 6 frames
    ImageRGBA8 image;       // the first frame (azimuth 0)
    std::string glRenderer; // the GL renderer VTK's window reported
};

class VtkAnchor {
public:
    // Writes `volume` (anchor.mhd + .raw), `preset` (its opacities per unit distance, as a
    // preset file holds them) and the script into a temporary folder. Throws
    // std::runtime_error naming what could not be written.
    VtkAnchor(const Volume& volume, const TransferFunction& preset);
    ~VtkAnchor();
    VtkAnchor(const VtkAnchor&) = delete;
    VtkAnchor& operator=(const VtkAnchor&) = delete;

    // Runs the anchor with `mapper` ("fixed" or "gpu") at width x height; unitMm > 0
    // takes the preset's opacities per unitMm (VTK's unit distance), else per voxel of
    // the smallest spacing (Lucent's). The first frame is written to `png` (empty: into
    // the temporary folder). Throws std::runtime_error saying what is missing (xvfb-run,
    // python3-vtk9) or what the script printed when it fails.
    VtkAnchorRun run(const std::string& mapper, double unitMm, int width = 512, int height = 512,
                     const std::filesystem::path& png = {}) const;

private:
    std::unique_ptr<QTemporaryDir> dir_;
    std::filesystem::path volume_, preset_, script_;
};

} // namespace lucent::bench
