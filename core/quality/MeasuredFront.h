#pragma once
// The quick front of one volume on one backend, measured once and kept in a
// cache file: a small sweep (quickSweep) at a reduced image size, whose times
// are scaled to the image size asked for. Keyed by the volume's fingerprint,
// the backend, the renderer version and what else changes the times (mode,
// shading, precision, leaping), so another volume, backend or renderer
// measures its own. Plain C++: the caller gives
// the cache folder (the user's cache dir in the app and the UI).

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/quality/QualityChoice.h"
#include "core/quality/QualityFront.h"

namespace lucent {

// Bump when a renderer change alters speed or images: older cache files are
// then measured again.
inline constexpr int kRendererVersion = 1;
// Bump when quickSweep() changes: fronts without the new settings are measured again.
inline constexpr int kQuickSweepVersion = 2;

// The image size a quick front is measured at.
inline constexpr int kQuickFrontSize = 128;

struct MeasuredFront {
    std::string key;
    int width = kQuickFrontSize; // the size the times were measured at
    int height = kQuickFrontSize;
    // The part of a frame's time that does not grow with the pixels, from the
    // fastest front point timed again at twice the size.
    double fixedMs = 0.0;
    std::vector<QualityPoint> points;

    // Requested pixels over measured pixels: the factor on the front's times.
    double timeScale(int requestedWidth, int requestedHeight) const;
    // The front's times at the requested size.
    TimeModel timeModel(int requestedWidth, int requestedHeight) const {
        return {timeScale(requestedWidth, requestedHeight), fixedMs};
    }
};

// The series UID with the dims, spacing, voxel type and a hash of (a lattice
// of) the voxels: equal for the same data, different for another volume.
std::string volumeFingerprint(const Volume& volume);

// A hash of the opacity curve of `tf` with its values rounded to 1/200 of the
// volume's value range (on a lattice of voxels) and its opacities to 0.05 (colours left out).
std::string opacityShape(const TransferFunction& tf, const Volume& volume);

// What a front depends on: volume, backend ("cpu", "gl"), renderer version,
// and the mode, shading, precision and empty-space leaping of `description`;
// for DVR also the opacity shape of its transfer function.
std::string frontKey(const RenderDescription& description, const std::string& backend);

// The cache file of `key` in `cacheDir` (a name from a hash of the key).
std::filesystem::path frontCachePath(const std::filesystem::path& cacheDir, const std::string& key);

// The cached front of `key`, or nullopt when there is none, it is for another
// key (a hash collision) or it does not parse.
std::optional<MeasuredFront> loadFront(const std::filesystem::path& cacheDir,
                                       const std::string& key);

// Writes the front (creating the folder); throws std::runtime_error naming
// the file when it cannot.
void saveFront(const std::filesystem::path& cacheDir, const MeasuredFront& front);

// Measures the quick front of `description` (its volume, TF, mode, camera and
// shading) with `render`, against `reference` (the CPU reference renderer).
MeasuredFront measureQuickFront(const RenderDescription& description, const std::string& backend,
                                const QualityRender& render, const QualityRender& reference,
                                const std::function<void(std::size_t, std::size_t)>& progress = {});

} // namespace lucent
