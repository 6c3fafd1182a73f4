#include "core/surface/SurfacePipeline.h"

#include <chrono>
#include <cmath>

#include "core/surface/FieldStats.h"
#include "core/surface/IsosurfaceExtractor.h"
#include "core/surface/MeshCleanup.h"

namespace lucent {
namespace {

using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

void check(const SurfaceRequest& r) {
    const auto fail = [](const std::string& what) { throw std::invalid_argument(what); };
    if (!std::isfinite(r.iso)) {
        fail("iso value is not a number");
    }
    if (!(r.maskSigma >= 0.0 && r.maskSigma <= 20.0)) {
        fail("mask smoothing sigma must be 0 to 20 voxels");
    }
    if (!(r.minComponentVoxels >= 0.0)) {
        fail("minimum component size must be 0 or more voxels");
    }
    if (r.smoothIterations < 0 || r.smoothIterations > 1000) {
        fail("smoothing iterations must be 0 to 1000");
    }
    if (!(r.smoothPassBand > 0.0 && r.smoothPassBand < 2.0)) {
        fail("smoothing pass band must lie in (0, 2)");
    }
    if (!(r.decimate >= 0.0 && r.decimate < 1.0)) {
        fail("decimation must remove a fraction in [0, 1) of the triangles");
    }
    if (!(r.svrRadius >= 0.0 && std::isfinite(r.svrRadius))) {
        fail("surface-to-volume radius must be 0 (none) or a positive number of mm");
    }
}

} // namespace

std::pair<double, double> surfaceFieldRange(const SvrField& field) {
    const FieldStats stats = fieldStats(field.svr);
    return {stats.p05, stats.p95 > stats.p05 ? stats.p95 : stats.p05 + 1e-9};
}

SurfaceResult makeSurface(const Volume& volume, const SurfaceRequest& request,
                          const std::function<bool(double, const char*)>& progress) {
    check(request);
    // Each step fills its share of the progress range.
    const bool svr = request.svrRadius > 0.0;
    const double extractEnd = svr ? 0.3 : 0.8, cleanupEnd = svr ? 0.4 : 1.0;
    const auto report = [&](double from, double to, const char* what) {
        return [&progress, from, to, what](double f) {
            return !progress || progress(from + (to - from) * f, what);
        };
    };
    SurfaceResult out;
    IsosurfaceOptions extraction;
    extraction.iso = request.iso;
    extraction.clip = request.clip;
    extraction.smoothingSigma = request.maskSigma;
    extraction.progress = report(0.0, extractEnd, "extracting the isosurface");
    try {
        IsosurfaceResult iso = extractIsosurface(volume, extraction);
        out.mesh = std::move(iso.mesh);
        out.extractMs = iso.extractMs;
        out.warnings = std::move(iso.warnings);
    } catch (const IsosurfaceCancelled&) {
        throw SurfaceCancelled();
    }

    const Clock::time_point cleanup = Clock::now();
    if (request.minComponentVoxels > 0.0 || request.keepLargest > 0) {
        const glm::dvec3 s = volume.geometry().spacing;
        ComponentFilter filter;
        filter.minVolume = request.minComponentVoxels * s.x * s.y * s.z;
        filter.keepLargest = request.keepLargest;
        out.componentsDropped = filterComponents(out.mesh, filter).componentsDropped;
    }
    if (request.smoothIterations > 0 && !out.mesh.empty()) {
        smoothWindowedSinc(out.mesh, {request.smoothIterations, request.smoothPassBand});
    }
    if (request.decimate > 0.0 && !out.mesh.empty()) {
        // meshoptimizer's collapses are not checked for topology: measured, on
        // CT bone they leave non-manifold and flipped edges. Said, not hidden.
        const MeshReport after = decimate(out.mesh, {1.0 - request.decimate, 1.0}).after;
        if (!after.closedManifold()) {
            if (svr) {
                throw std::invalid_argument(
                    "decimation left the mesh not closed and manifold (" +
                    std::to_string(after.boundaryEdges) + " boundary, " +
                    std::to_string(after.nonManifoldEdges) + " non-manifold, " +
                    std::to_string(after.repeatedDirectedEdges) +
                    " flipped edges): the surface-to-volume field needs a closed mesh; "
                    "compute it without decimation");
            }
            out.warnings.push_back("decimation left the mesh not closed and manifold (" +
                                   std::to_string(after.boundaryEdges) + " boundary, " +
                                   std::to_string(after.nonManifoldEdges) + " non-manifold, " +
                                   std::to_string(after.repeatedDirectedEdges) +
                                   " flipped edges); it may not print");
        }
    }
    out.cleanupMs = msSince(cleanup);
    if (progress && !progress(cleanupEnd, "cleaning up")) {
        throw SurfaceCancelled();
    }
    if (out.mesh.empty()) {
        throw std::runtime_error("no surface at iso " + std::to_string(request.iso) +
                                 " (nothing left after extraction and clean-up)");
    }
    out.report = checkMesh(out.mesh);

    if (svr) {
        SvrOptions options;
        options.progress = report(cleanupEnd, 1.0, "computing the surface-to-volume field");
        try {
            out.svr = computeSvrField(out.mesh, request.svrRadius, options);
        } catch (const SvrCancelled&) {
            throw SurfaceCancelled();
        }
        out.svrMs = out.svr->svrMs;
    }
    return out;
}

} // namespace lucent
