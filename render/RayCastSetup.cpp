#include "render/RayCastSetup_p.h"

#include <algorithm>
#include <cmath>

#include "core/raycast/BrickVisibility.h"
#include "render/GlObjects_p.h"

namespace lucent {

namespace {

// The specular power when it is a whole number the shader can multiply out, else 0.
int integerPower(const Shading& s) {
    const double p = s.specularPower;
    return p >= 1.0 && p <= 64.0 && p == std::floor(p) ? int(p) : 0;
}

int shaderMode(RenderMode m) {
    switch (m) {
    case RenderMode::Dvr:
        return 0;
    case RenderMode::Mip:
        return 1;
    case RenderMode::MinIp:
        return 2;
    case RenderMode::Average:
        return 3;
    case RenderMode::Isosurface:
        break;
    }
    return 4;
}

glm::dmat3 indexToPatient(const VolumeGeometry& g) {
    return {g.direction[0] * g.spacing.x, g.direction[1] * g.spacing.y,
            g.direction[2] * g.spacing.z};
}

// Whether every brick the table places is drawn from level 0 (the volume fits
// the budget): the shader then drops its per-brick level arithmetic.
bool onlyLevelZero(const BrickTable& table) {
    return std::all_of(table.perLevel.begin() +
                           std::min<std::ptrdiff_t>(1, std::ssize(table.perLevel)),
                       table.perLevel.end(), [](std::size_t n) { return n == 0; });
}

} // namespace

std::string rayCastDefines(const RayCastFrame& f) {
    const RenderDescription& desc = f.desc;
    const SamplingSettings& sampling = desc.sampling;
    const auto flag = [](bool b) { return b ? "true" : "false"; };
    const int interp = sampling.interpolation == Interpolation::Nearest ? 0
                       : sampling.interpolation == Interpolation::Cubic ? 2
                                                                        : 1;
    const bool leap = sampling.emptySpaceLeaping && (!f.overlay || desc.mode == RenderMode::Dvr);
    return "#define LUCENT_MODE " + std::to_string(shaderMode(desc.mode)) +
           "\n#define LUCENT_INTERP " + std::to_string(interp) + "\n#define LUCENT_PRECLASSIFY " +
           flag(sampling.classification == Classification::Pre) + "\n#define LUCENT_PREINTEGRATE " +
           flag(f.preintegrate) + "\n#define LUCENT_SHADING " +
           flag(desc.transferFunction.shading.enabled) + "\n#define LUCENT_LEAP " + flag(leap) +
           "\n#define LUCENT_CELLS_IN_ONE_BRICK " + flag(f.table.brickSize % kRayCellSize == 0) +
           "\n#define LUCENT_ONE_LEVEL " + flag(onlyLevelZero(f.table)) +
           "\n#define LUCENT_GRADIENT_TEXTURE " + flag(f.pool.hasGradients()) +
           "\n#define LUCENT_GRADIENT_IN_POOL " + flag(f.pool.gradientsShareTexture()) +
           "\n#define LUCENT_SPECULAR_INT " +
           std::to_string(integerPower(desc.transferFunction.shading)) +
           "\n#define LUCENT_ROW_SAMPLES " + flag(f.countRows) + "\n#define LUCENT_SURFACE " +
           flag(f.surface) + "\n#define LUCENT_OVERLAY " + flag(f.overlay) + "\n";
}

PixelRect rayPixels(const RayCastFrame& f) {
    const RenderDescription& desc = f.desc;
    if (f.surface) {
        return PixelRect{0, 0, desc.width - 1, desc.height - 1};
    }
    return pixelsOfBox(f.geometry, f.view, glm::max(desc.clip.lo, f.part.boxLo),
                       glm::min(desc.clip.hi, f.part.boxHi), desc.width, desc.height);
}

void setRayCastUniforms(const ShaderProgram& p, const RayCastFrame& f) {
    const RenderDescription& desc = f.desc;
    const VolumeGeometry& g = f.geometry;
    const glm::dmat3 linear = indexToPatient(g);
    const double dt = desc.sampling.step * std::min({g.spacing.x, g.spacing.y, g.spacing.z});
    p.set("uEye", g.toIndex(f.view.eye));
    p.set("uForward", f.view.forward);
    p.set("uRight", f.view.right);
    p.set("uUp", f.view.up);
    p.set("uToIndex", glm::inverse(linear));
    p.set("uTanHalfFov", f.view.tanHalfFov);
    p.set("uAspect", f.view.aspect);
    p.set("uImageSize", glm::ivec2(desc.width, desc.height));
    p.set("uDt", dt);
    p.set("uBoxLo", f.part.boxLo);
    p.set("uBoxHi", f.part.boxHi);
    p.set("uClipLo", glm::max(desc.clip.lo, f.part.boxLo));
    p.set("uClipHi", glm::min(desc.clip.hi, f.part.boxHi));
    p.set("uPart", f.isPart ? 1 : 0);
    p.set("uOpenHi", f.part.openHi);
    p.set("uSceneClipLo", f.part.sceneClipLo);
    p.set("uSceneClipHi", f.part.sceneClipHi);
    const Shading& light = desc.transferFunction.shading;
    p.set("uEarlyTermination", float(desc.sampling.earlyTermination));
    p.set("uIso", float(desc.isoValue));
    p.set("uLight", glm::vec4(light.ambient, light.diffuse, light.specular, light.specularPower));
    p.set("uGradientToWorld",
          glm::mat3(glm::transpose(glm::inverse(linear)) / gradientScale(f.valueLo, f.valueHi)));
    const double tLo = f.tableLo, tHi = f.tableHi;
    p.set("uVisibleLo", float(std::max(f.visibleLo, -3.0e38)));
    p.set("uVisibleHi", float(std::min(f.visibleHi, 3.0e38)));
    p.set("uStepRatio", float(desc.sampling.step));
    std::vector<glm::ivec3> levelDims = f.levelDims;
    levelDims.resize(8, levelDims.back());
    glUniform3iv(p.location("uLevelDims[0]"), 8, &levelDims[0].x);
    p.set("uBrickSize", f.table.brickSize);
    p.set("uInvBrickSize", 1.0f / float(f.table.brickSize));
    p.set("uBricksPerAxis", f.table.bricksPerAxis);
    p.set("uInvPoolSize", 1.0f / glm::vec3(f.pool.extent()));
    p.set("uValueScale", f.pool.format().valueScale);
    p.set("uGradientScale", float(f.gradientUnit * 32767.0));
    p.set("uTableSize", kRayTableSize);
    p.set("uTableLo", float(tLo));
    p.set("uTableScale", float(double(kRayTableSize - 1) / (tHi - tLo)));
    p.set("uPreSize", kRayPreintegrationSize);
    p.set("uPreLo", float(tLo));
    p.set("uPreHi", float(tHi));
    p.set("uCellSize", kRayCellSize);
    p.set("uInvCellSize", 1.0f / float(kRayCellSize));
    p.set("uCellsPerAxis", f.table.cellsPerAxis);
}

} // namespace lucent
