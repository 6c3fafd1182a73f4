#pragma once
// The server's render thread: one object that lives on a QThread, owns the EGL
// context (current on that thread for its whole life) or falls back to the
// CPU ray caster, loads the series that clients open, renders and encodes.

#include <QByteArray>
#include <QObject>
#include <QString>

#include <cstdint>
#include <list>
#include <memory>

#include "core/io/SeriesEntry.h"
#include "core/scene/RenderDescription.h"
#include "protocol/ProtocolMessages.h"

namespace lucent {
class OffscreenContext;
}

namespace lucent::remote {

enum class Backend { Gl, Cpu };

// One frame a view needs (a client's own view or a teaching session's).
struct RenderJob {
    quint64 view = 0;
    std::shared_ptr<const SeriesEntry> series;
    RenderDescription description; // the still description; volume left null
    Quality quality = Quality::Still;
    // Interactive frames: the image scale (the step doubles) and JPEG quality.
    double scale = 0.5;
    int jpegQuality = 85;
    std::uint64_t seq = 0;
};

struct RenderedFrame {
    quint64 view = 0;
    double frameMs = 0.0; // render plus encode
    std::uint64_t seq = 0;
    QByteArray message; // the binary frame message, ready to send; empty on error
    QString error;
};

// The `quality: interactive` frames: half the image size, twice the step, JPEG 85.
inline constexpr double kFixedInteractiveScale = 0.5;
inline constexpr int kFixedInteractiveJpegQuality = 85;

// The description of an interactive frame at this scale: the image's sides
// scaled (at least 1 pixel), the sampling step doubled.
RenderDescription scaledInteractiveDescription(const RenderDescription& still, double scale);

class RenderWorker : public QObject {
    Q_OBJECT
public:
    explicit RenderWorker(Backend backend);
    ~RenderWorker() override;

    // These run on the render thread (queued calls).
    // Makes the GL context current (GL backend) or settles on the CPU; says which.
    QString start();
    // Frees the ray casters and the context while the context is current.
    void stop();
    // Renders and encodes; emits frameRendered() (with an error on failure).
    void render(const lucent::remote::RenderJob& job);

signals:
    void frameRendered(const lucent::remote::RenderedFrame& frame);

private:
    struct LoadedSeries;
    // The loaded volume of exactly this entry: a series the store has grown since
    // (a new entry with the same id) is loaded again.
    LoadedSeries& loaded(const std::shared_ptr<const SeriesEntry>& entry);

    Backend backend_;
    std::unique_ptr<OffscreenContext> context_;
    std::list<std::unique_ptr<LoadedSeries>> loaded_; // most recently used first
};

} // namespace lucent::remote

Q_DECLARE_METATYPE(lucent::remote::RenderedFrame)
