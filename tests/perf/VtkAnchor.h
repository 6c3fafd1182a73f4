#pragma once
// VTK 9.1, the anchor of the render benchmarks (issue 31), run in the same
// benchmark as Lucent: tests/perf/vtk_anchor.py under xvfb-run (Debian's
// python3-vtk9, Mesa llvmpipe through GLX), on a MetaImage written by
// lucent-cli convert's writer. Mapper "fixed": vtkFixedPointVolumeRayCastMapper
// (2 threads), the CPU caster's anchor; "gpu": vtkGPUVolumeRayCastMapper, the
// GL caster's. Both render Lucent's scene: 512x512, the preset, shading,
// trilinear, step 0.5 voxel of the smallest spacing, Lucent's anterior camera,
// 6 frames turning 5 degrees.
#include <filesystem>
#include <string>

#include "core/image/Image.h"
#include "core/volume/Volume.h"

namespace lucent::bench {

struct VtkAnchorRun {
    double renderMs = 0.0; // median of the 6 frames
    ImageRGBA8 image;      // the first frame (azimuth 0)
};

// Writes `volume` as dir/anchor.mhd (+ .raw) for the anchor to read; returns the .mhd.
std::filesystem::path writeAnchorVolume(const Volume& volume, const std::filesystem::path& dir);

// Runs the anchor on `mhd` with `mapper` ("fixed" or "gpu"); unitMm > 0 takes
// the preset's opacities per unitMm (VTK's unit distance), else per voxel of the
// smallest spacing (Lucent's). The first frame is written to `png`. Throws
// std::runtime_error saying what is missing (xvfb-run, python3-vtk9) or what
// the script printed when it fails.
VtkAnchorRun runVtkAnchor(const std::filesystem::path& mhd, const std::string& mapper,
                          double unitMm, const std::filesystem::path& png);

} // namespace lucent::bench
