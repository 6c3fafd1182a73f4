#pragma once
// Pre-integration of one ray segment at a time, exactly (as preintegrateSegment
// in TransferFunction.h: split at every breakpoint, closed-form optical depth),
// for the double-precision reference renderer: no table, so a narrow spike of
// the transfer function keeps its full opacity at any step. Validates once,
// then each call costs a few breakpoints' work.

#include <memory>

#include <glm/glm.hpp>

#include "core/tf/TransferFunction.h"

namespace lucent {

class SegmentPreintegrator {
public:
    // Keeps a reference to `tf`, which must outlive it. Throws
    // std::invalid_argument for an invalid function or a stepRatio that is not
    // finite and above 0.
    SegmentPreintegrator(const TransferFunction& tf, double stepRatio);
    ~SegmentPreintegrator();
    SegmentPreintegrator(const SegmentPreintegrator&) = delete;
    SegmentPreintegrator& operator=(const SegmentPreintegrator&) = delete;

    // The segment from value sf (front) to sb (back): rgb premultiplied, alpha.
    glm::dvec4 operator()(double sf, double sb) const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
    double stepRatio_;
};

} // namespace lucent
