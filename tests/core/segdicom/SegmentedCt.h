#pragma once
// The real 140-slice CT (dcm_qa_ct/Philips_S21570/S2020) with segments drawn on it the ways
// Lucent makes them: thresholds and islands (semi-automatic, automatic), a hand-drawn ball
// (manual, a UTF-8 name), a segment coded outside Lucent's table, and an empty one.

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "core/io/Catalog.h"
#include "core/report/ReferencedSeries.h"
#include "core/segmentation/SegmentEffects.h"
#include "core/segmentation/Segmentation.h"
#include "tests/support/RealData.h"

namespace lucent::test {

inline constexpr const char* kSegmentedCt = "dcm_qa_ct/Philips_S21570/S2020";

inline std::vector<std::filesystem::path> segmentedCtFiles() {
    std::vector<std::filesystem::path> files;
    for (const auto& e : std::filesystem::directory_iterator(kRealData / kSegmentedCt)) {
        files.push_back(e.path());
    }
    std::sort(files.begin(), files.end());
    return files;
}

// Voxels within radiusMm of the patient point `centre`.
inline SegmentMask ballMask(const VolumeGeometry& grid, const glm::dvec3& centre, double radiusMm) {
    SegmentMask mask(grid.dims);
    for (int k = 0; k < grid.dims.z; ++k) {
        for (int j = 0; j < grid.dims.y; ++j) {
            for (int i = 0; i < grid.dims.x; ++i) {
                if (glm::length(grid.toPatient(glm::dvec3(i, j, k)) - centre) <= radiusMm) {
                    mask.set(mask.linearIndex(i, j, k));
                }
            }
        }
    }
    return mask;
}

// `extra` more threshold segments (for the benchmark's ten) after the five described above.
inline Segmentation segmentedCt(const Volume& ct, int extra = 0) {
    Segmentation seg(ct.geometry());
    const std::uint32_t bone = seg.add("Skull", findSegmentKind("bone"));
    seg.setMask(bone, keepLargestIsland(thresholdMask(ct, 300.0, 3000.0)), "Threshold",
                "Lucent threshold");
    const std::uint32_t soft = seg.add("Soft tissue", findSegmentKind("tissue"));
    seg.setMask(soft, removeSmallIslands(thresholdMask(ct, -100.0, 100.0), ct.geometry(), 500.0),
                "Islands", "Lucent islands", true);
    const std::uint32_t ball = seg.add("Läsion ø12", findSegmentKind("lesion"));
    seg.setMask(ball, ballMask(ct.geometry(), volumeCentre(ct.geometry()), 12.0), "Paint");
    const std::uint32_t brain = seg.add("Brain");
    seg.setKind(brain, SegmentKind{"brain",
                                   {"123037004", "SCT", "Anatomical Structure"},
                                   {"12738006", "SCT", "Brain"},
                                   0xf0c080});
    seg.setColour(brain, {250, 250, 225});
    seg.setMask(brain, thresholdMask(ct, 20.0, 45.0), "Threshold", "Lucent threshold");
    seg.add("Nothing yet", findSegmentKind("liver")); // stays empty
    for (int n = 0; n < extra; ++n) {
        const std::uint32_t id = seg.add("Band " + std::to_string(n));
        const double lo = -900.0 + 150.0 * n;
        seg.setMask(id, thresholdMask(ct, lo, lo + 140.0), "Threshold", "Lucent threshold");
    }
    return seg;
}

} // namespace lucent::test
