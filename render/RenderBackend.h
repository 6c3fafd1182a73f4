#pragma once

#include <array>
#include <optional>
// What turns a RenderDescription into a frame for the 3D view: the local GPU
// (or CPU) ray caster, or a lucent-server over WebSocket. The view asks with
// request(); a frame comes back later with frameReady(). The newest request
// wins: a backend may skip older ones, and a frame says whether it shows the
// newest request (current) or an older one still on its way.

#include <cstdint>
#include <memory>

#include <QObject>
#include <QString>

#include "core/image/Image.h"
#include "core/quality/InteractiveQuality.h"
#include "core/raycast/CpuRayCaster.h"
#include "core/scene/RenderDescription.h"

namespace lucent {

struct FrameOptions {
    // While the user drags: a coarser, smaller frame (the view scales it up).
    bool interactive = false;
    // How much coarser, for backends that choose (the local one); a server
    // applies its own.
    InteractiveQuality quality;
};

struct BackendFrame {
    ImageRGBA8 image; // as rendered: an interactive frame is smaller than the view
    // Drawn straight into the view's framebuffer (the local GPU ray caster):
    // no image; LocalRenderBackend::readLastFrame() reads it back on request.
    bool inPlace = false;
    RenderStats stats;
    bool interactive = false;
    bool current = true;   // it shows the newest request
    double renderMs = 0.0; // where the renderer reports it
    int jpegQuality = 0;   // a server's JPEG quality; 0: lossless
    double scale = 1.0;    // the image's size against the view's, as the renderer chose it
    // A server's frame (protocol version 4): the 3 x 4 matrix taking LPS mm to image
    // fractions (core/scene/ImageProjection.h), where a session's marks lie on it.
    std::optional<std::array<double, 12>> projection;
};

// Where the backend stands; local backends are always Ready, a remote one
// Disconnected until it is told where to connect.
enum class BackendStatus { Ready, Disconnected, Connecting, Connected, Reconnecting, Failed };
inline const char* backendStatusName(BackendStatus status) {
    switch (status) {
    case BackendStatus::Ready:
        return "ready";
    case BackendStatus::Disconnected:
        return "disconnected";
    case BackendStatus::Connecting:
        return "connecting";
    case BackendStatus::Connected:
        return "connected";
    case BackendStatus::Reconnecting:
        return "reconnecting";
    case BackendStatus::Failed:
        return "failed";
    }
    return "unknown";
}

class RenderBackend : public QObject {
    Q_OBJECT

public:
    using QObject::QObject;
    ~RenderBackend() override = default;

    // The volume the next requests describe (their `volume` points to it). The
    // backend keeps it alive.
    virtual void setVolume(std::shared_ptr<const Volume> volume) = 0;
    // Asks for a frame of `still` (or of its interactive version). The newest
    // request wins; frames of older ones may still arrive (current = false).
    virtual void request(const RenderDescription& still, const FrameOptions& options) = 0;
    virtual BackendStatus status() const { return BackendStatus::Ready; }

signals:
    // The frame is the backend's again once the receivers return: a receiver
    // copies what it keeps (the local backend lends its buffers to the next frame).
    void frameReady(const lucent::BackendFrame& frame);
    // A request that could not be rendered (a bad setting, a server's refusal).
    void frameFailed(const QString& reason);
    // Connection changes (remote backends): the message says why, in words.
    void statusChanged(lucent::BackendStatus status, const QString& message);
};

} // namespace lucent
