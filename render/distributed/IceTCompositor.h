#pragma once
// Sort-last compositing of the ranks' partial images with IceT (Moreland et
// al.): every rank renders its part of the volume into a full-size image, and
// IceT combines them, rank 0 receiving the result. RAII over IceT's
// communicator and context. Every rank calls every composite, in the same
// order, with the same size and order (collectives).
//
// Images are w x h pixels, row-major, premultiplied RGBA in float, over
// transparent black (the background is added once, after compositing).

#include <chrono>
#include <cstddef>
#include <memory>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "render/distributed/Communicator.h"

namespace lucent {

// What the last composite cost.
struct CompositeFigures {
    double compositeMs = 0.0; // IceT's composite time on this rank
    double totalMs = 0.0;     // the whole call, on this rank
    double bytesSent = 0.0;   // by this rank
};

class IceTCompositor {
public:
    // IceT's communicator and context over `comm`, which must outlive this.
    // Throws std::runtime_error when IceT fails.
    explicit IceTCompositor(const Communicator& comm);
    ~IceTCompositor();
    IceTCompositor(const IceTCompositor&) = delete;
    IceTCompositor& operator=(const IceTCompositor&) = delete;

    // Ordered "over" blending: frontToBack lists every rank once, nearest the
    // eye first. Returns the composite on rank 0 (empty elsewhere): a view of
    // IceT's buffer (or of `rgba` with one rank), valid until the next
    // composite. Not copied: a fresh 16 MiB buffer a frame costs more than
    // IceT's compositing at 1024x1024 (page faults, measured).
    std::span<const glm::vec4> blend(int width, int height, std::span<const glm::vec4> rgba,
                                     std::span<const int> frontToBack);
    // Per pixel, the rank with the smallest depth wins (depth in [0, 1]; 1:
    // nothing there). Returns the winners' colours on rank 0 (a view, as
    // blend()), and their depths in `depthOut` when given (rank 0).
    std::span<const glm::vec4> closest(int width, int height, std::span<const glm::vec4> rgba,
                                       std::span<const float> depth,
                                       std::vector<float>* depthOut = nullptr);

    const CompositeFigures& last() const { return last_; }
    const char* strategyName() const;

private:
    // IceT's figures of the composite just done, and the time since start.
    void recordFigures(std::chrono::steady_clock::time_point start);
    struct State;
    std::unique_ptr<State> state_;
    CompositeFigures last_;
};

} // namespace lucent
