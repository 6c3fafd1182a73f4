#include "render/distributed/IceTCompositor.h"

#include <mpi.h>

#include <IceT.h>
#include <IceTMPI.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <stdexcept>
#include <string>

namespace lucent {

struct IceTCompositor::State {
    const Communicator* comm = nullptr;
    IceTCommunicator icetComm = ICET_COMM_NULL;
    IceTContext context = nullptr;
    int width = 0, height = 0;
    IceTEnum mode = 0;

    ~State() {
        if (context != nullptr) {
            icetDestroyContext(context);
        }
        if (icetComm != ICET_COMM_NULL) {
            icetDestroyMPICommunicator(icetComm);
        }
    }
};

namespace {

void checkIceT(const char* what) {
    const IceTEnum error = icetGetError();
    if (error == ICET_NO_ERROR) {
        return;
    }
    const char* name = error == ICET_SANITY_CHECK_FAIL   ? "sanity check failed"
                       : error == ICET_INVALID_ENUM      ? "invalid enum"
                       : error == ICET_BAD_CAST          ? "bad cast"
                       : error == ICET_OUT_OF_MEMORY     ? "out of memory"
                       : error == ICET_INVALID_OPERATION ? "invalid operation"
                       : error == ICET_INVALID_VALUE     ? "invalid value"
                                                         : "unknown error";
    throw std::runtime_error(std::string("IceT: ") + what + ": " + name);
}

void checkImage(int width, int height, std::size_t pixels) {
    if (width < 1 || height < 1 || std::size_t(width) * std::size_t(height) != pixels) {
        throw std::invalid_argument("IceT composite: an image of " + std::to_string(pixels) +
                                    " pixels for " + std::to_string(width) + " x " +
                                    std::to_string(height));
    }
}

} // namespace

IceTCompositor::IceTCompositor(const Communicator& comm) : state_(std::make_unique<State>()) {
    state_->comm = &comm;
    state_->icetComm = icetCreateMPICommunicator(MPI_Comm_f2c(MPI_Fint(comm.fortranHandle())));
    if (state_->icetComm == ICET_COMM_NULL) {
        throw std::runtime_error("IceT: icetCreateMPICommunicator failed");
    }
    state_->context = icetCreateContext(state_->icetComm);
    icetDiagnostics(ICET_DIAG_ERRORS | ICET_DIAG_ALL_NODES);
    // One tile, pre-rendered images: SEQUENTIAL honours the composite order;
    // radix-k within it (Peterka et al. 2009).
    icetStrategy(ICET_STRATEGY_SEQUENTIAL);
    icetSingleImageStrategy(ICET_SINGLE_IMAGE_STRATEGY_RADIXK);
    icetSetColorFormat(ICET_IMAGE_COLOR_RGBA_FLOAT);
    checkIceT("creating the context");
}

IceTCompositor::~IceTCompositor() = default;

const char* IceTCompositor::strategyName() const {
    return "sequential/radix-k";
}

namespace {

// The tile and formats for this composite; IceT keeps them between frames.
void prepare(int width, int height, IceTEnum mode, int& w0, int& h0, IceTEnum& mode0) {
    if (width != w0 || height != h0) {
        icetResetTiles();
        icetAddTile(0, 0, width, height, 0);
        w0 = width;
        h0 = height;
    }
    if (mode != mode0) {
        icetCompositeMode(mode);
        if (mode == ICET_COMPOSITE_MODE_BLEND) {
            icetSetDepthFormat(ICET_IMAGE_DEPTH_NONE);
            icetEnable(ICET_ORDERED_COMPOSITE);
        } else {
            icetSetDepthFormat(ICET_IMAGE_DEPTH_FLOAT);
            icetDisable(ICET_ORDERED_COMPOSITE);
        }
        mode0 = mode;
    }
    checkIceT("setting the tile and formats");
}

// The rectangle (x, y, width, height; rows in buffer order) holding every
// pixel that `used` says is drawn: IceT reads and compresses nothing outside
// it. One pixel for an image with none.
template <class Used> std::array<IceTInt, 4> validViewport(int width, int height, Used used) {
    int x0 = width, x1 = -1, y0 = height, y1 = -1;
    for (int y = 0; y < height; ++y) {
        const std::size_t row = std::size_t(y) * std::size_t(width);
        int first = -1, last = -1;
        for (int x = 0; x < width; ++x) {
            if (used(row + std::size_t(x))) {
                first = first < 0 ? x : first;
                last = x;
            }
        }
        if (first >= 0) {
            x0 = std::min(x0, first);
            x1 = std::max(x1, last);
            y0 = std::min(y0, y);
            y1 = std::max(y1, y);
        }
    }
    if (x1 < 0) {
        return {0, 0, 1, 1};
    }
    return {x0, y0, x1 - x0 + 1, y1 - y0 + 1};
}

// The composite's colour in IceT's buffer (RGBA float, the format set).
std::span<const glm::vec4> colourOf(IceTImage image, std::size_t pixels) {
    if (std::size_t(icetImageGetNumPixels(image)) != pixels) {
        throw std::runtime_error("IceT: the composite has " +
                                 std::to_string(icetImageGetNumPixels(image)) + " pixels, not " +
                                 std::to_string(pixels));
    }
    const auto* colour = reinterpret_cast<const glm::vec4*>(icetImageGetColorcf(image));
    checkIceT("reading the composite");
    return {colour, pixels};
}

const IceTDouble kIdentity[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
const IceTFloat kTransparent[4] = {0, 0, 0, 0};

} // namespace

std::span<const glm::vec4> IceTCompositor::blend(int width, int height,
                                                 std::span<const glm::vec4> rgba,
                                                 std::span<const int> frontToBack) {
    const auto start = std::chrono::steady_clock::now();
    checkImage(width, height, rgba.size());
    if (int(frontToBack.size()) != state_->comm->size()) {
        throw std::invalid_argument("IceT composite: an order of " +
                                    std::to_string(frontToBack.size()) + " ranks for " +
                                    std::to_string(state_->comm->size()));
    }
    if (state_->comm->size() == 1) {
        last_ = {};
        return rgba; // nothing to composite
    }
    icetSetContext(state_->context);
    prepare(width, height, ICET_COMPOSITE_MODE_BLEND, state_->width, state_->height, state_->mode);
    const std::vector<IceTInt> order(frontToBack.begin(), frontToBack.end());
    icetCompositeOrder(order.data());
    const auto valid =
        validViewport(width, height, [&](std::size_t i) { return rgba[i].a > 0.0f; });
    const IceTImage image =
        icetCompositeImage(rgba.data(), nullptr, valid.data(), kIdentity, kIdentity, kTransparent);
    checkIceT("icetCompositeImage (blend)");
    std::span<const glm::vec4> out;
    if (state_->comm->rank() == 0 && !icetImageIsNull(image)) {
        out = colourOf(image, rgba.size());
    }
    recordFigures(start);
    return out;
}

std::span<const glm::vec4> IceTCompositor::closest(int width, int height,
                                                   std::span<const glm::vec4> rgba,
                                                   std::span<const float> depth,
                                                   std::vector<float>* depthOut) {
    const auto start = std::chrono::steady_clock::now();
    checkImage(width, height, rgba.size());
    checkImage(width, height, depth.size());
    if (state_->comm->size() == 1) {
        last_ = {};
        if (depthOut != nullptr) {
            depthOut->assign(depth.begin(), depth.end());
        }
        return rgba; // nothing to composite
    }
    icetSetContext(state_->context);
    prepare(width, height, ICET_COMPOSITE_MODE_Z_BUFFER, state_->width, state_->height,
            state_->mode);
    // IceT drops the depths of the result unless asked for them.
    if (depthOut != nullptr) {
        icetDisable(ICET_COMPOSITE_ONE_BUFFER);
    } else {
        icetEnable(ICET_COMPOSITE_ONE_BUFFER);
    }
    const auto valid = validViewport(width, height, [&](std::size_t i) { return depth[i] < 1.0f; });
    const IceTImage image = icetCompositeImage(rgba.data(), depth.data(), valid.data(), kIdentity,
                                               kIdentity, kTransparent);
    checkIceT("icetCompositeImage (depth)");
    std::span<const glm::vec4> out;
    if (state_->comm->rank() == 0 && !icetImageIsNull(image)) {
        out = colourOf(image, rgba.size());
        if (depthOut != nullptr) {
            depthOut->resize(depth.size());
            icetImageCopyDepthf(image, depthOut->data(), ICET_IMAGE_DEPTH_FLOAT);
        }
        checkIceT("copying the composite");
    }
    recordFigures(start);
    return out;
}

void IceTCompositor::recordFigures(std::chrono::steady_clock::time_point start) {
    icetGetDoublev(ICET_COMPOSITE_TIME, &last_.compositeMs);
    last_.compositeMs *= 1000.0;
    IceTInt sent = 0;
    icetGetIntegerv(ICET_BYTES_SENT, &sent);
    last_.bytesSent = double(sent);
    last_.totalMs =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

} // namespace lucent
