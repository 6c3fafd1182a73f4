#pragma once
// The server's render thread: one object that lives on a QThread, has its
// FrameSource (this process, or the ranks of an MPI job) draw the frames that
// clients' views need, and encodes them.

#include <QByteArray>
#include <QObject>
#include <QString>

#include <cstdint>
#include <memory>

#include "core/io/SeriesEntry.h"
#include "core/scene/RenderDescription.h"
#include "protocol/ProtocolMessages.h"
#include "server/FrameSource.h"
#include "server/SliceFrames.h"

namespace lucent::remote {

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

class RenderWorker : public QObject {
    Q_OBJECT
public:
    explicit RenderWorker(std::unique_ptr<FrameSource> frames);
    ~RenderWorker() override;

    // These run on the render thread (queued calls).
    // Opens what renders (FrameSource::start()); says what.
    QString start();
    // Frees the ray casters and the context while the context is current.
    void stop();
    // Renders and encodes; emits frameRendered() (with an error on failure).
    void render(const lucent::remote::RenderJob& job);
    // MPR slices of the series' whole volume; emits slicesRendered() (with an error on failure).
    void renderSlices(const lucent::remote::SliceJob& job);

signals:
    void frameRendered(const lucent::remote::RenderedFrame& frame);
    void slicesRendered(const lucent::remote::RenderedSlices& slices);

private:
    std::unique_ptr<FrameSource> frames_;
    bool started_ = false;
};

} // namespace lucent::remote

Q_DECLARE_METATYPE(lucent::remote::RenderedFrame)
