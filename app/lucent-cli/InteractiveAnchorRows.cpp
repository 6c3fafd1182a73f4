// lucent-cli bench interactive, Lucent against its anchors (issue 31, b and c), as
// bench_gpu_render againstVtkGpu and bench_cpu_render run them: per opacity unit, --runs runs
// with Lucent and the anchors alternating (the load of a shared machine comes and goes), each
// run's times, their ratio and both dB against the converged reference.
#include <QTextStream>

#include <functional>
#include <memory>
#include <optional>

#include "InteractiveRows.h"
#include "app/bench/BenchFrames.h"
#include "app/bench/BenchScenes.h"
#include "app/bench/VolPackAnchor.h"
#include "app/bench/VtkAnchor.h"
#include "core/image/ImageMetrics.h"
#include "core/raycast/CpuRayCaster.h"
#include "render/GpuRayCaster.h"

namespace lucent::cli {

namespace {

// What one side of a row measured: ms and dB against the reference, or why not.
struct Side {
    std::optional<double> ms;
    double db = 0.0;
    std::string cell;
};

Side measured(double ms, const ImageRGBA8& image, const ImageRGBA8& reference,
              const std::string& note = "") {
    const double db = psnr(image, reference);
    return {ms, db, msCell(ms) + ", " + dbCell(db) + note};
}

Side missing(const std::string& why) {
    return {std::nullopt, 0.0, why};
}

// The anchor's message on one line, short enough for a cell.
std::string failed(const std::exception& e) {
    std::string text = std::string("not run: ") + e.what();
    for (char& c : text) {
        c = c == '\n' ? ' ' : c;
    }
    return text.size() > 240 ? text.substr(0, 237) + "..." : text;
}

Side vtkSide(const InteractiveDevices& devices, const std::string& mapper, double unitMm,
             const RenderDescription& d, const ImageRGBA8& reference) {
    if (!devices.vtk) {
        return missing(devices.vtkMissing);
    }
    try {
        const bench::VtkAnchorRun v = devices.vtk->run(mapper, unitMm, d.width, d.height);
        return measured(v.renderMs, v.image, reference,
                        mapper == "gpu" ? " (GL: " + v.glRenderer + ")" : " (2 threads)");
    } catch (const std::exception& e) {
        return missing(failed(e));
    }
}

// The row of Lucent against an anchor: ratio of the times; `met` judges it when both ran.
InteractiveRow versus(std::string what, const Side& lucent, const Side& anchor, std::string goal,
                      const std::function<bool(double ratio)>& met) {
    InteractiveRow row{std::move(what), lucent.cell, anchor.cell, "-", std::move(goal), "-"};
    if (lucent.ms && anchor.ms) {
        const double ratio = *lucent.ms / *anchor.ms;
        row.ratio = ratioCell(ratio);
        if (met) {
            row.met = metCell(met(ratio));
        }
    }
    return row;
}

InteractiveRows glAgainstVtk(const Volume& volume, const RenderDescription& d, double unitMm,
                             const ImageRGBA8& reference, const InteractiveSettings& s,
                             const InteractiveDevices& devices) {
    std::unique_ptr<GpuRayCaster> gpu;
    std::string why = devices.glMissing;
    if (why.empty()) {
        try {
            gpu = std::make_unique<GpuRayCaster>(volume);
        } catch (const std::exception& e) {
            why = std::string("failed: ") + e.what();
        }
    }
    InteractiveRows rows;
    for (int run = 1; run <= s.runs; ++run) {
        Side lucent = missing(why);
        if (gpu) {
            try {
                const bench::TurnFrames f = bench::turnFrames(*gpu, d);
                lucent = measured(f.medianMs, f.first.frame.image, reference);
            } catch (const std::exception& e) {
                lucent = missing(std::string("failed: ") + e.what());
            }
        }
        const Side vtk = vtkSide(devices, "gpu", unitMm, d, reference);
        rows.push_back(versus("GL vs VTK GPU mapper, run " + std::to_string(run) + "/" +
                                  std::to_string(s.runs) + ", " + unitName(unitMm),
                              lucent, vtk, "<= 0.10", [](double r) { return r <= 0.10; }));
    }
    return rows;
}

InteractiveRows cpuAgainstAnchors(const Volume& volume, const RenderDescription& d, double unitMm,
                                  const ImageRGBA8& reference, const InteractiveSettings& s,
                                  const InteractiveDevices& devices) {
    CpuRayCaster cpu(volume);
    // VolPack classifies once, outside the timing (Lucent caches its classification).
    std::optional<bench::VolPackAnchor> volpack;
    std::string volpackWhy = "skipped (--no-anchors)";
    if (s.anchors) {
        try {
            volpack.emplace(volume, d.transferFunction, d.camera, d.width, d.height);
        } catch (const std::exception& e) {
            volpackWhy = e.what();
        }
    }
    InteractiveRows rows;
    for (int run = 1; run <= s.runs; ++run) {
        const std::string of =
            ", run " + std::to_string(run) + "/" + std::to_string(s.runs) + ", " + unitName(unitMm);
        const bench::TurnFrames f = bench::turnFrames(cpu, d);
        const Side lucent = measured(f.medianMs, f.first.frame.image, reference);
        const Side vtk = vtkSide(devices, "fixed", unitMm, d, reference);
        rows.push_back(versus("CPU vs VTK fixed-point" + of, lucent, vtk,
                              "<= 0.12 at >= VTK + 10 dB",
                              [&](double r) { return r <= 0.12 && lucent.db >= vtk.db + 10.0; }));
        Side shearWarp = missing(volpackWhy);
        if (volpack) {
            const bench::TurnFrames v = bench::turnFrames(
                [&](const RenderDescription& frame) {
                    GpuRenderResult r;
                    r.frame.image = volpack->render(frame.camera);
                    return r;
                },
                d);
            shearWarp = measured(v.medianMs, v.first.frame.image, reference, " (1 thread)");
        }
        rows.push_back(versus("CPU vs VolPack shear-warp (parallel projection)" + of, lucent,
                              shearWarp, "-", {}));
    }
    return rows;
}

} // namespace

InteractiveRows anchorRows(const Volume& volume, const InteractiveSettings& s,
                           const InteractiveDevices& devices) {
    QTextStream err(stderr);
    InteractiveRows rows;
    for (const double unit : s.unitsMm) {
        const RenderDescription d = bench::ctBoneScene(volume, unit, s.size.x, s.size.y);
        err << "bench interactive: the converged reference, " << unitName(unit).c_str() << "\n"
            << Qt::flush;
        const ImageRGBA8 reference = CpuRayCaster(volume).render(bench::converged(d)).image;
        const InteractiveRows gl = glAgainstVtk(volume, d, unit, reference, s, devices);
        rows.insert(rows.end(), gl.begin(), gl.end());
        const InteractiveRows cpu = cpuAgainstAnchors(volume, d, unit, reference, s, devices);
        rows.insert(rows.end(), cpu.begin(), cpu.end());
    }
    return rows;
}

} // namespace lucent::cli
