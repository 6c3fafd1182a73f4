#include "server/SliceStream.h"

#include <algorithm>

#include "core/mpr/CrosshairSlice.h"
#include "core/mpr/WindowPresets.h"
#include "server/ClientConnection.h"
#include "server/RenderServer.h"
#include "server/ViewStream.h"

namespace lucent::remote {

int sliceChannel(Orientation view) {
    return 1 + static_cast<int>(view);
}

SliceStream::SliceStream(ViewStream& view, RenderServer& server) : view_(view), server_(server) {}

void SliceStream::reset() {
    ++generation_;
    active_ = false;
    crosshair_.reset();
    window_.reset();
    wanted_ = false;
    lastFrames_ = {};
}

void SliceStream::apply(const SlicesRequest& request) {
    if (request.crosshair) {
        crosshair_ = *request.crosshair;
    }
    if (request.windowPreset) {
        if (const WindowPreset* preset = findWindowPreset(*request.windowPreset)) {
            window_ = SliceWindow{preset->center, preset->width};
        }
    } else if (request.window) {
        window_ = *request.window;
    }
    if (request.size) {
        size_ = *request.size;
    }
    if (request.views) {
        views_ = *request.views;
        for (std::size_t i = 0; i < lastFrames_.size(); ++i) {
            if (std::find(views_.begin(), views_.end(), static_cast<Orientation>(i)) ==
                views_.end()) {
                lastFrames_[i].clear(); // a later member is not sent a view no longer shown
            }
        }
    }
    active_ = true;
    ++seq_;
    wanted_ = true;
    pump();
}

void SliceStream::pump() {
    const auto& series = view_.series();
    ClientConnection* pacer = view_.pacer();
    if (!wanted_ || inFlight_ || !active_ || !series || views_.empty() || !pacer ||
        !pacer->readyForFrame()) {
        return;
    }
    wanted_ = false;
    inFlight_ = true;
    // Inside the voxel-centre box: every plane through it shows the volume.
    const glm::dvec3 crosshair =
        clampToVolume(series->geometry, crosshair_.value_or(volumeCentre(series->geometry)));
    crosshair_ = crosshair;
    server_.submitSlices(
        SliceJob{view_.id(), series, views_, crosshair, window_, size_, seq_, generation_});
}

void SliceStream::deliver(const RenderedSlices& slices) {
    inFlight_ = false;
    if (slices.generation != generation_ || !view_.series()) {
        pump();
        return;
    }
    ClientConnection* pacer = view_.pacer();
    if (!slices.error.isEmpty()) {
        // The reason may name a file; only the controller reads it.
        for (const auto& member : view_.members()) {
            if (member && member->version() >= 4) {
                member->sendError("render-failed",
                                  member == pacer ? slices.error.toStdString()
                                                  : std::string("the slices could not be rendered"),
                                  false);
            }
        }
    } else {
        window_ = slices.window; // the volume's default, once chosen, stays
        for (const auto& [orientation, frame] : slices.frames) {
            lastFrames_[static_cast<std::size_t>(orientation)] = frame;
            for (const auto* watchers : {&view_.members(), &view_.onlookers()}) {
                for (const auto& member : *watchers) {
                    if (member && member->version() >= 4) {
                        member->offerFrame(frame, sliceChannel(orientation));
                    }
                }
            }
        }
    }
    pump();
}

void SliceStream::offerLastFrames(ClientConnection& member) const {
    if (member.version() < 4) {
        return;
    }
    for (std::size_t i = 0; i < lastFrames_.size(); ++i) {
        if (!lastFrames_[i].isEmpty()) {
            member.offerFrame(lastFrames_[i], sliceChannel(static_cast<Orientation>(i)));
        }
    }
}

} // namespace lucent::remote
