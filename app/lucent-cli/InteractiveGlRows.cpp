// lucent-cli bench interactive, the GL caster's rows (issue 31, a, d and e): the tiled cube at
// full quality, the long volume in its budget, a surface with the volume, the default path's
// memory and the CPU time of a camera-only frame.
#include <chrono>
#include <cstdio>
#include <memory>

#include "InteractiveRows.h"
#include "app/bench/BenchFrames.h"
#include "app/bench/BenchScenes.h"
#include "core/scene/SurfaceDisplay.h"
#include "core/surface/IsosurfaceExtractor.h"
#include "core/surface/MeshCleanup.h"
#include "render/GpuRayCaster.h"

namespace lucent::cli {

namespace {

using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

std::string sizeText(glm::ivec2 s) {
    return std::to_string(s.x) + "x" + std::to_string(s.y);
}

std::string dimsText(glm::ivec3 d) {
    return std::to_string(d.x) + "x" + std::to_string(d.y) + "x" + std::to_string(d.z);
}

std::string mib(std::size_t bytes) {
    char text[32];
    const double v = double(bytes) / 1048576.0;
    std::snprintf(text, sizeof text, v >= 100.0 ? "%.0f MiB" : "%.1f MiB", v);
    return text;
}

// ", level L" when the frame was drawn coarser than the volume (a budget too small).
std::string levelNote(const bench::TurnFrames& f) {
    return f.first.frame.stats.lod > 0 ? ", level " + std::to_string(f.first.frame.stats.lod) : "";
}

struct CubeVariant {
    const char* name;
    Interpolation interpolation;
    bool preintegrate;
    double goalMs;
};

constexpr CubeVariant kCubeVariants[] = {
    {"tricubic + shading", Interpolation::Cubic, false, 16.7},
    {"tricubic + shading + pre-integration", Interpolation::Cubic, true, 16.7},
    {"trilinear + shading", Interpolation::Linear, false, 8.0},
};

std::string goalMsText(double ms) {
    char text[32];
    std::snprintf(text, sizeof text, "<= %g ms", ms);
    return text;
}

// The cube's frames for one variant and opacity unit, timed against the variant's goal.
InteractiveRow cubeRow(GpuRayCaster& gpu, const Volume& cube, const InteractiveSettings& s,
                       const CubeVariant& v, double unitMm, const std::string& what) {
    RenderDescription d = bench::ctBoneScene(cube, unitMm, s.cubeSize.x, s.cubeSize.y);
    d.sampling.interpolation = v.interpolation;
    d.sampling.preintegrate = v.preintegrate;
    const bench::TurnFrames f = bench::turnFrames(gpu, d);
    char fps[32];
    std::snprintf(fps, sizeof fps, " (%.1f fps", 1000.0 / f.medianMs);
    return goalRow(what, msCell(f.medianMs) + fps + levelNote(f) + ")", goalMsText(v.goalMs),
                   f.medianMs <= v.goalMs);
}

} // namespace

InteractiveRows glCubeRows(const Volume& volume, const InteractiveSettings& s,
                           const InteractiveDevices& devices) {
    std::string why = devices.glMissing;
    std::unique_ptr<Volume> cube;
    std::unique_ptr<GpuRayCaster> gpu;
    if (why.empty()) {
        try {
            cube = std::make_unique<Volume>(bench::tiled(volume, glm::ivec3(s.cube)));
            gpu = std::make_unique<GpuRayCaster>(*cube);
        } catch (const std::exception& e) {
            why = std::string("failed: ") + e.what();
        }
    }
    InteractiveRows rows;
    for (const double unit : s.unitsMm) {
        for (const CubeVariant& v : kCubeVariants) {
            const std::string what = "GL " + dimsText(glm::ivec3(s.cube)) + " (tiled), " +
                                     sizeText(s.cubeSize) + ", " + v.name + ", " + unitName(unit);
            try {
                rows.push_back(gpu ? cubeRow(*gpu, *cube, s, v, unit, what)
                                   : missingRow(what, goalMsText(v.goalMs), why));
            } catch (const std::exception& e) {
                rows.push_back(
                    missingRow(what, goalMsText(v.goalMs), std::string("failed: ") + e.what()));
            }
        }
    }
    return rows;
}

InteractiveRows glLongRows(const Volume& volume, const InteractiveSettings& s,
                           const InteractiveDevices& devices) {
    const std::string scene = "GL " + dimsText(s.longDims) + " (tiled) in " +
                              mib(s.longBudgetBytes) + ", " + sizeText(s.size);
    const std::string firstWhat = scene + ": first frame after load (caster made + frame 0)";
    const std::string fpsWhat = scene + ": frames a second (median of 6 turning)";
    const std::string firstGoal = "<= 2000 ms", fpsGoal = ">= 30 fps";
    std::string why = devices.glMissing;
    if (s.skipLarge) {
        why = "skipped (--skip-large)";
    }
    if (!why.empty()) {
        return {missingRow(firstWhat, firstGoal, why), missingRow(fpsWhat, fpsGoal, why)};
    }
    try {
        const Volume big = bench::tiled(volume, s.longDims);
        GpuOptions options;
        options.budgetBytes = s.longBudgetBytes;
        const auto t0 = Clock::now();
        GpuRayCaster gpu(big, options);
        const double openMs = msSince(t0);
        const bench::TurnFrames f =
            bench::turnFrames(gpu, bench::ctBoneScene(big, 0.0, s.size.x, s.size.y));
        const double firstMs = openMs + f.firstMs;
        const double fps = 1000.0 / f.medianMs;
        char fpsText[32];
        std::snprintf(fpsText, sizeof fpsText, "%.1f fps", fps);
        return {goalRow(firstWhat,
                        msCell(firstMs) + " (caster " + msCell(openMs) + " + frame " +
                            msCell(f.firstMs) + levelNote(f) + ")",
                        firstGoal, firstMs <= 2000.0),
                goalRow(fpsWhat,
                        std::string(fpsText) + " (" + msCell(f.medianMs) + levelNote(f) + ")",
                        fpsGoal, fps >= 30.0)};
    } catch (const std::exception& e) {
        const std::string failed = std::string("failed: ") + e.what();
        return {missingRow(firstWhat, firstGoal, failed), missingRow(fpsWhat, fpsGoal, failed)};
    }
}

InteractiveRows glSurfaceRows(const Volume& volume, const InteractiveSettings& s,
                              const InteractiveDevices& devices) {
    char what[160];
    std::snprintf(what, sizeof what,
                  "GL with a surface of ~%zu triangles (iso %g), %s: ms added a frame",
                  s.surfaceTriangles, s.surfaceIso, sizeText(s.size).c_str());
    const std::string goal = "<= 2 ms";
    if (!devices.glMissing.empty()) {
        return {missingRow(what, goal, devices.glMissing)};
    }
    try {
        IsosurfaceOptions iso;
        iso.iso = s.surfaceIso;
        auto mesh = std::make_shared<TriangleMesh>(extractIsosurface(volume, iso).mesh);
        if (mesh->triangles.size() > s.surfaceTriangles) {
            DecimationOptions fewer;
            fewer.targetFraction = double(s.surfaceTriangles) / double(mesh->triangles.size());
            decimate(*mesh, fewer);
        }
        auto display = std::make_shared<SurfaceDisplay>();
        display->mesh = mesh;
        GpuRayCaster gpu(volume);
        const RenderDescription d = bench::ctBoneScene(volume, 0.0, s.size.x, s.size.y);
        const bench::TurnFrames without = bench::turnFrames(gpu, d);
        gpu.setSurface(display);
        const bench::TurnFrames with = bench::turnFrames(gpu, d);
        const double added = with.medianMs - without.medianMs;
        return {goalRow(what,
                        msCell(added) + " (" + std::to_string(mesh->triangles.size()) +
                            " triangles: " + msCell(without.medianMs) + " -> " +
                            msCell(with.medianMs) + ")",
                        goal, added <= 2.0)};
    } catch (const std::exception& e) {
        return {missingRow(what, goal, std::string("failed: ") + e.what())};
    }
}

InteractiveRows defaultPathRows(const Volume& volume, const InteractiveSettings& s,
                                const InteractiveDevices& devices) {
    const std::string memoryWhat = "GL default path: GPU memory (resident + tables) / volume";
    const std::string glWhat =
        "GL: CPU time outside the cast, camera-only drag (prepare_ms, median of 12)";
    const std::string cpuWhat = "CPU caster: time outside the cast, camera-only drag, frames "
                                "handed back (outside_cast_ms, median of 12)";
    const RenderDescription d = bench::ctBoneScene(volume, 0.0, s.size.x, s.size.y);
    InteractiveRows rows;
    if (!devices.glMissing.empty()) {
        rows = {missingRow(memoryWhat, "<= 200 %", devices.glMissing),
                missingRow(glWhat, "<= 0.5 ms", devices.glMissing)};
    } else {
        try {
            GpuRayCaster gpu(volume);
            const bench::DragOverhead o = bench::dragOverhead(gpu, d);
            const GpuFrameStats& g = gpu.lastFrame();
            const double share =
                100.0 * double(g.residentBytes + g.tableBytes) / double(volume.byteCount());
            char pct[32];
            std::snprintf(pct, sizeof pct, "%.0f %%", share);
            rows.push_back(goalRow(memoryWhat,
                                   std::string(pct) + " (" + mib(g.residentBytes) + " + " +
                                       mib(g.tableBytes) + " of " + mib(volume.byteCount()) +
                                       "; gradients " +
                                       (g.gradientsCached ? "cached" : "computed") + ")",
                                   "<= 200 %", share <= 200.0));
            rows.push_back(goalRow(glWhat,
                                   msCell(o.outsideCastMs) + " (cast " + msCell(o.castMs) + ")",
                                   "<= 0.5 ms", o.outsideCastMs <= 0.5));
        } catch (const std::exception& e) {
            const std::string failed = std::string("failed: ") + e.what();
            rows = {missingRow(memoryWhat, "<= 200 %", failed),
                    missingRow(glWhat, "<= 0.5 ms", failed)};
        }
    }
    CpuRayCaster cpu(volume);
    const bench::DragOverhead c = bench::dragOverhead(cpu, d);
    rows.push_back(goalRow(cpuWhat, msCell(c.outsideCastMs) + " (cast " + msCell(c.castMs) + ")",
                           "<= 0.5 ms", c.outsideCastMs <= 0.5));
    return rows;
}

} // namespace lucent::cli
