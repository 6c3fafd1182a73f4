// RemoteRenderBackend: the view (the series chosen and opened, the view
// messages that changed, paced and counted) and the frames that show it.
#include <algorithm>

#include <QImage>

#include "protocol/ProtocolMessages.h"
#include "render/RemoteRenderBackend.h"
#include "render/RemoteRenderBackend_p.h"

namespace lucent {

namespace {

// Camera keys that servers of version 1 before its camera distance and pan refuse.
constexpr std::string_view kCentreKeys[] = {"distance", "pan_right", "pan_up"};

bool offCentre(const remote::CameraUpdate& camera) {
    return std::any_of(std::begin(kCentreKeys), std::end(kCentreKeys), [&](std::string_view key) {
        return camera.number(key).value_or(0.0) != 0.0;
    });
}

ImageRGBA8 toImage(const QImage& decoded) {
    const QImage q = decoded.convertToFormat(QImage::Format_RGBA8888);
    ImageRGBA8 out = ImageRGBA8::filled(q.width(), q.height());
    for (int y = 0; y < q.height(); ++y) {
        std::copy_n(q.constScanLine(y), 4 * q.width(), out.at(0, y));
    }
    return out;
}

} // namespace

void RemoteRenderBackend::sendView(const std::string& type, const std::string& json) {
    send(json);
    ++seqSent_;
    // A new value of a refused kind may be accepted (an unnamed refusal: any).
    refused_.remove(text(type));
    refused_.remove(QString());
}

void RemoteRenderBackend::chooseSeries() {
    const QString wanted = !settings_.series.isEmpty() ? settings_.series
                           : volume_                   ? QString::fromStdString(volume_->seriesUid)
                                                       : QString();
    if (wanted.isEmpty()) {
        fail(tr("no volume is loaded and the settings name no series"));
        return;
    }
    // The server names further parts of one UID "UID#n": the one of our size.
    QString chosen;
    for (const OfferedSeries& s : offered_) {
        if (s.uid == wanted) {
            chosen = s.uid;
            break;
        }
        if (chosen.isEmpty() && s.uid.startsWith(wanted + "#") && volume_ &&
            s.dims == volume_->dims()) {
            chosen = s.uid;
        }
    }
    if (chosen.isEmpty()) {
        fail(tr("%1 does not have series %2 (it offers %3 series)")
                 .arg(where(), wanted)
                 .arg(offered_.size()));
        return;
    }
    phase_ = Phase::Opening;
    sent_.clear(); // everything goes out again
    interacting_ = false;
    sentOffCentre_ = false;
    refused_.clear();
    // The server counts view messages per connection, across re-opens: the
    // count goes on, and frames of the series before are older than the new
    // view's first (firstViewSeq_, set by the first sync).
    firstViewSeq_ = 0;
    sendView("open", remote::writeClientMessage(remote::OpenRequest{chosen.toStdString()}));
}

void RemoteRenderBackend::setVolume(std::shared_ptr<const Volume> volume) {
    volume_ = std::move(volume);
    wanted_.reset();
    if (!follow_ &&
        (phase_ == Phase::Open || phase_ == Phase::Opening || phase_ == Phase::Listing)) {
        // Open the new volume's series (or the one the settings name) again.
        phase_ = Phase::Listing;
        cameraTimer_.stop();
        send(remote::writeClientMessage(remote::ListRequest{}));
    }
}

void RemoteRenderBackend::request(const RenderDescription& still, const FrameOptions& options) {
    wanted_ = WantedView{still, options.interactive};
    sync();
}

void RemoteRenderBackend::sync() {
    if (phase_ != Phase::Open || !wanted_ || cameraTimer_.isActive() ||
        (follow_ && followState_ != FollowState::LookingAround)) {
        return;
    }
    const RenderDescription& d = wanted_->still;
    std::vector<remote::ClientMessage> messages = remote::viewMessages(d);
    if (follow_) { // in free look the session's transfer function, mode and clip box stay
        std::erase_if(messages, [](const remote::ClientMessage& m) {
            return !std::holds_alternative<remote::CameraUpdate>(m) &&
                   !std::holds_alternative<remote::SizeUpdate>(m);
        });
    }
    for (remote::ClientMessage& m : messages) {
        auto* camera = std::get_if<remote::CameraUpdate>(&m);
        // A version 1 server before camera distance and pan refuses those keys:
        // they go once the view has left the orbit about the centre, and to such a
        // server nothing else is lost.
        if (camera && serverVersion_ < 2 && !offCentre(*camera) && !sentOffCentre_) {
            std::erase_if(camera->values, [](const remote::OptionValue& v) {
                return std::find(std::begin(kCentreKeys), std::end(kCentreKeys),
                                 v.option->wireKey) != std::end(kCentreKeys);
            });
        }
        // Camera messages are paced; the rest waits with them so that a still
        // frame never shows an old camera.
        if (camera && sent_.count("camera") && sent_["camera"] != remote::writeClientMessage(m) &&
            cameraClock_.isValid() && cameraClock_.elapsed() < kCameraIntervalMs) {
            cameraTimer_.start(int(kCameraIntervalMs - cameraClock_.elapsed()));
            return;
        }
    }
    // A drag is an interaction: adaptive JPEG frames until its end, which owes
    // one lossless still (after `open` the server is not interacting). The
    // start goes before the changes and the end after them, so that no still
    // is rendered for a half-way camera.
    const bool interacting = interacting_;
    if (wanted_->interactive && !interacting) {
        sendView("interaction", remote::writeClientMessage(remote::InteractionUpdate{true}));
    }
    interacting_ = wanted_->interactive;
    for (const remote::ClientMessage& m : messages) {
        const std::string type(remote::messageType(m));
        const std::string json = remote::writeClientMessage(m);
        if (const auto it = sent_.find(type); it != sent_.end() && it->second == json) {
            continue;
        }
        sent_[type] = json;
        if (remote::messageVersion(m) > serverVersion_) {
            refuseNewerMessage(type, json, d);
            continue;
        }
        sendView(type, json);
        if (const auto* camera = std::get_if<remote::CameraUpdate>(&m)) {
            sentOffCentre_ = sentOffCentre_ || offCentre(*camera);
            cameraClock_.start();
        }
    }
    if (!wanted_->interactive && interacting) {
        sendView("interaction", remote::writeClientMessage(remote::InteractionUpdate{false}));
    }
    if (firstViewSeq_ == 0) {
        firstViewSeq_ = seqSent_;
    }
}

void RemoteRenderBackend::refuseNewerMessage(const std::string& type, const std::string& json,
                                             const RenderDescription& wanted) {
    // Only sampling is newer than version 1. The server renders with the
    // sampling a description has by default (shading: the transfer function's):
    // a view that asks for that loses nothing.
    RenderDescription server;
    server.transferFunction = wanted.transferFunction;
    const remote::SamplingUpdate theirs{remote::optionUpdate(kWireSampling, server)};
    if (type != "sampling" || json == remote::writeClientMessage(theirs)) {
        if (refused_.remove(text(type))) {
            // The frames since the refusal show the view wanted now: one more says so.
            sendView("render", remote::writeClientMessage(remote::RenderRequest{}));
        }
        return;
    }
    QStringList settings;
    for (const remote::OptionValue& v : remote::optionUpdate(kWireSampling, wanted).values) {
        if (theirs.text(v.option->wireKey) != v.text) {
            settings << QString::fromUtf8(v.option->name.data(), qsizetype(v.option->name.size())) +
                            " " + text(v.text);
        }
    }
    refused_.insert(text(type));
    emit frameFailed(tr("%1 speaks protocol version %2, which cannot carry the sampling settings "
                        "(%3): it renders with its own (sampling needs version %4)")
                         .arg(where())
                         .arg(serverVersion_)
                         .arg(settings.join(", "))
                         .arg(remote::messageTypeVersion(type)));
}

void RemoteRenderBackend::onBinary(const QByteArray& message) {
    try {
        const auto frame = remote::parseFrameMessage(
            std::string_view(message.constData(), std::size_t(message.size())));
        // A follower shows every frame of the session; its own view's (free look) from
        // free-look-started on.
        const bool ownView = !follow_ || followState_ == FollowState::LookingAround;
        if (phase_ != Phase::Open || frame.header.slice ||
            (ownView && (firstViewSeq_ == 0 || frame.header.seq < firstViewSeq_))) {
            return; // the server's defaults, a series no longer wanted, or an MPR slice (v4)
        }
        QImage decoded;
        const char* format = frame.header.format == "png" ? "PNG" : "JPEG";
        if (!decoded.loadFromData(reinterpret_cast<const uchar*>(frame.image.data()),
                                  int(frame.image.size()), format)) {
            emit frameFailed(tr("a %1 frame from the server cannot be decoded").arg(format));
            return;
        }
        BackendFrame out;
        out.image = toImage(decoded);
        out.interactive = frame.header.quality == remote::Quality::Interactive;
        // Not the view the user wants while a paced camera waits for its timer
        // or a refused change has not been replaced.
        out.current = !ownView || (frame.header.seq == seqSent_ && !cameraTimer_.isActive() &&
                                   refused_.isEmpty());
        out.renderMs = frame.header.renderMs;
        out.jpegQuality = frame.header.format == "jpeg" ? frame.header.jpegQuality : 0;
        out.scale = frame.header.scale;
        out.projection = frame.header.projection;
        emit frameReady(out);
    } catch (const std::exception& e) {
        emit frameFailed(tr("a frame from the server cannot be read: %1").arg(e.what()));
    }
}

} // namespace lucent
