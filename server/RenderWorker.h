#pragma once
// The server's render thread: one object that lives on a QThread, has its
// FrameSource (this process, or the ranks of an MPI job) draw the frames that
// clients' views need, and encodes them.

#include <QByteArray>
#include <QObject>
#include <QString>

#include <cstdint>
#include <memory>
#include <vector>

#include <glm/glm.hpp>

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
    // A follower's free look: rendered when the render thread has nothing else
    // to do (RenderServer::submit()); a still may then be made cheaper.
    bool background = false;
    bool mayDegrade = false; // background only: a still may become an interactive frame
    bool degraded = false;   // it did (the server was busy)
};

struct RenderedFrame {
    quint64 view = 0;
    double frameMs = 0.0; // render plus encode
    std::uint64_t seq = 0;
    QByteArray message; // the binary frame message, ready to send; empty on error
    QString error;
    bool degraded = false; // a still made interactive because the server was busy
};

// One mark of a view to anchor on the surface its points show (ViewMarks).
struct AnchorJob {
    quint64 view = 0;
    std::uint64_t ticket = 0; // the view's number for this mark
    std::shared_ptr<const SeriesEntry> series;
    RenderDescription description; // the still description; volume left null
    std::vector<glm::dvec2> fractions;
};
struct FoundAnchors {
    quint64 view = 0;
    std::uint64_t ticket = 0;
    std::vector<glm::dvec3> anchors; // LPS mm; empty on error
    QString error;
};

// The `quality: interactive` frames: half the image size, twice the step, JPEG 85.
inline constexpr double kFixedInteractiveScale = 0.5;
inline constexpr int kFixedInteractiveJpegQuality = 85;
// A free look's interactive frame while the server is busy: at most this.
inline constexpr double kBusyInteractiveScale = 0.5;
inline constexpr int kBusyInteractiveJpegQuality = 60;

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
    // Anchors a mark; emits anchorsFound() (with an error on failure).
    void anchor(const lucent::remote::AnchorJob& job);
    // MPR slices of the series' whole volume; emits slicesRendered() (with an error on failure).
    void renderSlices(const lucent::remote::SliceJob& job);

signals:
    void frameRendered(const lucent::remote::RenderedFrame& frame);
    void anchorsFound(const lucent::remote::FoundAnchors& found);
    void slicesRendered(const lucent::remote::RenderedSlices& slices);

private:
    std::unique_ptr<FrameSource> frames_;
    bool started_ = false;
};

} // namespace lucent::remote

Q_DECLARE_METATYPE(lucent::remote::RenderedFrame)
Q_DECLARE_METATYPE(lucent::remote::FoundAnchors)
