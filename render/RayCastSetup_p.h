#pragma once
// What the ray-casting shader is compiled with (#defines) and given
// (uniforms) for a frame: the CPU ray caster's set-up in the shader's terms.
// Private to render/.

#include <string>
#include <vector>

#include "core/scene/RenderDescription.h"
#include "core/scene/ViewFrame.h"
#include "render/BrickPool.h"
#include "render/BrickTable.h"
#include "render/PartFrame_p.h"

namespace lucent {

class ShaderProgram;

constexpr int kRayTableSize = 4096; // as the CPU ray caster's float path
constexpr int kRayPreintegrationSize = 256;
constexpr int kRayCellSize = 8; // the finer leaping level, as on the CPU (BrickStreamer's cells)

struct RayCastFrame {
    const RenderDescription& desc;
    const VolumeGeometry& geometry; // of the volume (a part's own)
    const ViewFrame& view;
    const PartFrame& part;
    bool isPart = false;
    const BrickTable& table;
    const BrickPool& pool;
    std::vector<glm::ivec3> levelDims;   // at most 8
    double tableLo = 0.0, tableHi = 1.0; // the classification tables' range
    // The values a sample may show (visibleValueRange, widened by a table cell).
    double visibleLo = -1e300, visibleHi = 1e300;
    double valueLo = 0.0, valueHi = 1.0; // the volume's
    double gradientUnit = 1.0;           // of a cached gradient component of 1
    bool preintegrate = false, countRows = false, surface = false, overlay = false;
};

std::string rayCastDefines(const RayCastFrame& f);
// The pixels whose rays can meet the clip box (pixelsOfBox, as the CPU caster
// casts): the others keep the cleared target, what a ray that misses leaves.
// The whole image with a surface, which every pixel shows.
PixelRect rayPixels(const RayCastFrame& f);
void setRayCastUniforms(const ShaderProgram& p, const RayCastFrame& f);

} // namespace lucent
