#include "server/RenderWorker.h"

#include <QBuffer>
#include <QElapsedTimer>
#include <QImage>
#include <QImageWriter>

#include "core/quality/InteractiveQuality.h"
#include "core/scene/ImageProjection.h"
#include "core/scene/ViewFrame.h"
#include "protocol/PngEncoder.h"

namespace lucent::remote {
namespace {

double millisecondsSince(const QElapsedTimer& timer) {
    return double(timer.nsecsElapsed()) / 1e6;
}

// PNG (lossless) or JPEG of an opaque RGBA image; throws std::runtime_error.
QByteArray encode(const ImageRGBA8& image, Quality quality, int jpegQuality) {
    if (quality == Quality::Still) {
        const std::string png = encodePng(image.pixels, image.width, image.height);
        return QByteArray(png.data(), qsizetype(png.size()));
    }
    const QImage rgba(image.pixels.data(), image.width, image.height, image.width * 4,
                      QImage::Format_RGBA8888);
    const QImage rgb = rgba.convertToFormat(QImage::Format_RGB888);
    QByteArray bytes;
    QBuffer buffer(&bytes);
    buffer.open(QIODevice::WriteOnly);
    QImageWriter writer(&buffer, "jpeg");
    writer.setQuality(jpegQuality);
    if (!writer.write(rgb)) {
        throw std::runtime_error("image encoding failed: " + writer.errorString().toStdString());
    }
    return bytes;
}

} // namespace

RenderWorker::RenderWorker(std::unique_ptr<FrameSource> frames) : frames_(std::move(frames)) {}

RenderWorker::~RenderWorker() {
    stop();
}

QString RenderWorker::start() {
    started_ = true;
    return frames_->start();
}

void RenderWorker::stop() {
    if (started_) {
        frames_->stop();
        started_ = false;
    }
}

void RenderWorker::render(const RenderJob& job) {
    RenderedFrame frame;
    frame.view = job.view;
    frame.seq = job.seq;
    frame.degraded = job.degraded;
    RenderResult rendered;
    try {
        RenderDescription description = job.description;
        const bool interactive = job.quality == Quality::Interactive;
        if (interactive) {
            description = interactiveDescription(description, InteractiveQuality{2.0, job.scale});
        }
        QElapsedTimer timer;
        timer.start();
        rendered = frames_->render(job.series, description);
        const ImageRGBA8& image = rendered.image;
        FrameHeader header;
        header.renderMs = millisecondsSince(timer);
        timer.restart();
        const QByteArray encoded = encode(image, job.quality, job.jpegQuality);
        header.encodeMs = millisecondsSince(timer);
        frame.frameMs = header.renderMs + header.encodeMs;
        header.scale = interactive ? job.scale : 1.0;
        header.jpegQuality = interactive ? job.jpegQuality : 0;
        header.width = image.width;
        header.height = image.height;
        header.format = interactive ? "jpeg" : "png";
        header.seq = job.seq;
        header.quality = job.quality;
        // Where a mark's anchors lie on this image (clients draw marks over it).
        header.projection = imageProjection(makeViewFrame(job.series->geometry, description.camera,
                                                          description.width, description.height));
        const std::string message = frameMessage(
            header, std::string_view(encoded.constData(), std::size_t(encoded.size())));
        frame.message = QByteArray(message.data(), qsizetype(message.size()));
    } catch (const std::exception& e) {
        frame.error = QString::fromUtf8(e.what());
    }
    if (frame.error.isEmpty()) {
        frames_->recycle(job.series, std::move(rendered)); // encoded: it may draw the next
    }
    emit frameRendered(frame);
}

void RenderWorker::anchor(const AnchorJob& job) {
    FoundAnchors found;
    found.view = job.view;
    found.ticket = job.ticket;
    try {
        found.anchors = frames_->surfaceAnchors(job.series, job.description, job.fractions);
    } catch (const std::exception& e) {
        found.error = QString::fromUtf8(e.what());
    }
    emit anchorsFound(found);
}

void RenderWorker::renderSlices(const SliceJob& job) {
    RenderedSlices slices;
    try {
        slices = renderSliceFrames(frames_->volume(job.series), job);
    } catch (const std::exception& e) {
        slices.view = job.view;
        slices.seq = job.seq;
        slices.generation = job.generation;
        slices.error = QString::fromUtf8(e.what());
    }
    emit slicesRendered(slices);
}

} // namespace lucent::remote
