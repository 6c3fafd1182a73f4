#include "server/ViewStream.h"

#include "core/scene/ViewFrame.h"

#include "core/scene/DefaultPreset.h"
#include "server/ClientConnection.h"
#include "server/RenderServer.h"
#include "server/ViewMarks.h"

namespace lucent::remote {

ViewStream::ViewStream(quint64 id, RenderServer& server, QObject* parent)
    : QObject(parent), id_(id), server_(server), marks_(std::make_unique<ViewMarks>(*this, server)),
      slices_(std::make_unique<SliceStream>(*this, server)) {
    server_.registerView(this);
}

ViewStream::~ViewStream() {
    server_.unregisterView(id_);
}

void ViewStream::addMember(ClientConnection* client) {
    if (!members_.contains(client)) {
        members_.append(client);
    }
}

void ViewStream::removeMember(ClientConnection* client) {
    members_.removeAll(client);
    members_.removeAll(nullptr);
    if (pacer_ == client) {
        pacer_ = nullptr;
    }
}

void ViewStream::setPacer(ClientConnection* client) {
    if (client != pacer_) {
        marks_->hidePointer();
    }
    pacer_ = client;
}

void ViewStream::addOnlooker(ClientConnection* client) {
    onlookers_.removeAll(nullptr);
    if (!onlookers_.contains(client)) {
        onlookers_.append(client);
    }
}

void ViewStream::removeOnlooker(ClientConnection* client) {
    onlookers_.removeAll(client);
    onlookers_.removeAll(nullptr);
}

int ViewStream::memberCount() const {
    int n = 0;
    for (const auto& m : members_) {
        n += m ? 1 : 0;
    }
    return n;
}

std::string ViewStream::open(std::shared_ptr<const SeriesEntry> series) {
    reset(*series);
    return show(std::move(series));
}

void ViewStream::reset(const SeriesEntry& like) {
    const int width = description_.width, height = description_.height;
    series_.reset();
    opening_ = true;
    description_ = RenderDescription{};
    description_.width = width;
    description_.height = height;
    preset_ = defaultPresetName(like.modality, description_.mode);
    description_.transferFunction = loadPreset(preset_);
    quality_ = Quality::Still;
    interacting_ = false;
    stillOwed_ = false;
    lastFrame_.clear();
    marks_->clear(false); // marks lie on the series they were placed on
    slices_->reset();
    changed();
}

std::string ViewStream::show(std::shared_ptr<const SeriesEntry> series) {
    series_ = std::move(series);
    opening_ = false;
    renderWanted_ = true;
    // The volume's bounding sphere, which zoom 1 fits: clients turn pixels into pan mm.
    const std::string opened = writeServerMessage(Opened{series_->id, series_->geometry.dims,
                                                         volumeRadius(series_->geometry), preset_,
                                                         volumeCentre(series_->geometry)});
    // The caller sends `opened` first; the frame follows from the event loop.
    QMetaObject::invokeMethod(this, &ViewStream::pump, Qt::QueuedConnection);
    return opened;
}

void ViewStream::startAsCopyOf(const ViewStream& session) {
    series_ = session.series_;
    opening_ = session.opening_;
    preset_ = session.preset_;
    description_ = session.description_;
    quality_ = session.quality_;
    seq_ = session.seq_;
    background_ = true;
    renderWanted_ = true;
    pump();
}

void ViewStream::close() {
    marks_->clear(false);
    series_.reset();
    opening_ = false;
    renderWanted_ = false;
    lastFrame_.clear();
    slices_->reset();
}

std::optional<std::string> ViewStream::apply(const ClientMessage& message) {
    // Size, transfer function, mode, clip, camera and sampling: the description.
    if (auto error = applyViewMessage(message, description_)) {
        return error;
    }
    if (const auto* quality = std::get_if<QualityUpdate>(&message)) {
        quality_ = quality->quality;
    } else if (const auto* interaction = std::get_if<InteractionUpdate>(&message)) {
        stillOwed_ = !interaction->active;
        interacting_ = interaction->active;
    }
    // RenderRequest: nothing changes but a frame is owed.
    changed();
    return std::nullopt;
}

void ViewStream::changed() {
    ++seq_;
    renderWanted_ = true;
    pump();
}

void ViewStream::pump() {
    slices_->pump();
    if (!renderWanted_ || renderInFlight_ || !series_ || !pacer_ || !pacer_->readyForFrame()) {
        return;
    }
    renderWanted_ = false;
    renderInFlight_ = true;
    RenderJob job{
        id_, series_, description_, quality_, kFixedInteractiveScale, kFixedInteractiveJpegQuality,
        seq_};
    adaptiveInFlight_ = false;
    job.background = background_;
    job.mayDegrade = background_ && !std::exchange(upgradeOwed_, false);
    if (stillOwed_) {
        job.quality = Quality::Still;
        stillOwed_ = false;
    } else if (interacting_) {
        const InteractiveSetting setting = adaptive_.current();
        job.quality = Quality::Interactive;
        job.scale = setting.scale;
        job.jpegQuality = setting.jpegQuality;
        adaptiveInFlight_ = true;
    }
    server_.submit(job);
}

void ViewStream::deliver(const RenderedFrame& frame) {
    renderInFlight_ = false;
    if (!frame.error.isEmpty()) {
        // The reason may name a file; only the pacer (owner or presenter) reads it.
        for (const auto& member : std::as_const(members_)) {
            if (member) {
                member->sendError("render-failed",
                                  member == pacer_ ? frame.error.toStdString()
                                                   : std::string("the frame could not be rendered"),
                                  false);
            }
        }
    } else if (series_) {
        if (adaptiveInFlight_ && !frame.degraded) { // a cheaper frame says nothing of the view
            adaptive_.record(frame.frameMs);
        }
        if (frame.degraded && !renderWanted_ && !interacting_) {
            // Made cheaper while the server was busy: the full still when it is not.
            stillOwed_ = true;
            upgradeOwed_ = true;
            renderWanted_ = true;
        }
        lastFrame_ = frame.message;
        for (const auto& member : std::as_const(members_)) {
            if (member) {
                member->offerFrame(lastFrame_);
            }
        }
    }
    pump();
}

} // namespace lucent::remote
