#pragma once
// lucent-cli bench interactive: the rows of issue 31's goal table ("Interactive at full
// quality"), each measured on the benchmarks' scene (app/bench/BenchScenes.h) with
// lucent_bench's frames and anchors, as tests/perf's benchmarks measure them. A row whose
// device or anchor is missing says why in its cells; no figure is ever made up.

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/volume/Volume.h"

namespace lucent {
class OffscreenContext;
namespace bench {
class VtkAnchor;
}
} // namespace lucent

namespace lucent::cli {

struct InteractiveRow {
    std::string what, lucent, anchor = "-", ratio = "-", goal, met = "-";
};
using InteractiveRows = std::vector<InteractiveRow>;

struct InteractiveSettings {
    glm::ivec2 size{512, 512};           // --size: the scene's rows and the anchors'
    int cube = 512;                      // --cube: the tiled cube's side
    glm::ivec2 cubeSize{1024, 1024};     // --cube-size
    glm::ivec3 longDims{512, 512, 5382}; // --long-dims
    std::size_t longBudgetBytes = std::size_t(2048) << 20; // --long-budget (MiB)
    bool skipLarge = false;                                // --skip-large: no long volume
    std::size_t surfaceTriangles = 700000;                 // --surface-triangles
    double surfaceIso = 300.0;                             // --surface-iso
    int runs = 3;                                          // --runs
    std::vector<double> unitsMm{0.0, 1.0};                 // --units: 0 per voxel, 1 per mm
    bool anchors = true;                                   // --no-anchors
};

// What the rows run on: the GL context (or why there is none), the VTK anchor (or why not).
struct InteractiveDevices {
    std::unique_ptr<OffscreenContext> gl;
    std::string glMissing; // empty when gl is there
    std::unique_ptr<bench::VtkAnchor> vtk;
    std::string vtkMissing; // empty when vtk is there
    InteractiveDevices();
    ~InteractiveDevices();
    InteractiveDevices(InteractiveDevices&&) noexcept;
};

// "per voxel" or "per mm" (or "per N mm").
std::string unitName(double unitMm);

// The cells: "12.3 ms", "41.2 dB", "0.082", "yes"/"no".
std::string msCell(double ms);
std::string dbCell(double db);
std::string ratioCell(double ratio);
std::string metCell(bool met);

// A row whose measurement could not be made: `why` in the Lucent cell.
InteractiveRow missingRow(std::string what, std::string goal, const std::string& why);
// A row of Lucent alone (no anchor), its goal met or not.
InteractiveRow goalRow(std::string what, std::string lucent, std::string goal, bool met);

// a. The GL caster: the cube (tricubic + shading, + pre-integration, trilinear + shading) at
// the cube size, per opacity unit; the long volume in its budget (first frame, frames a
// second); a surface of about surfaceTriangles with the volume (ms added).
InteractiveRows glCubeRows(const Volume& volume, const InteractiveSettings& s,
                           const InteractiveDevices& devices);
InteractiveRows glLongRows(const Volume& volume, const InteractiveSettings& s,
                           const InteractiveDevices& devices);
InteractiveRows glSurfaceRows(const Volume& volume, const InteractiveSettings& s,
                              const InteractiveDevices& devices);
// b and c. Lucent against its anchors, --runs runs alternating per opacity unit: GL against
// VTK's GPU mapper, the CPU caster against VTK's fixed-point mapper and VolPack; dB against
// the converged reference.
InteractiveRows anchorRows(const Volume& volume, const InteractiveSettings& s,
                           const InteractiveDevices& devices);
// d and e. The default GL path's memory (resident + tables / volume) and the CPU time of a
// camera-only frame outside the cast, GL and CPU.
InteractiveRows defaultPathRows(const Volume& volume, const InteractiveSettings& s,
                                const InteractiveDevices& devices);

} // namespace lucent::cli
