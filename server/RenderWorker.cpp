#include "server/RenderWorker.h"

#include <QBuffer>
#include <QElapsedTimer>
#include <QImage>
#include <QImageWriter>

#include "core/io/Catalog.h"
#include "core/quality/InteractiveQuality.h"
#include "protocol/PngEncoder.h"
#include "render/RenderDevice.h"

namespace lucent::remote {
namespace {

// Series kept loaded (with their ray casters) at once.
constexpr std::size_t kLoadedSeriesLimit = 2;

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

struct RenderWorker::LoadedSeries {
    std::shared_ptr<const SeriesEntry> entry; // held: its address identifies it
    std::unique_ptr<Volume> volume;
    std::unique_ptr<Renderer> renderer;
};

RenderWorker::RenderWorker(RendererKind backend) : backend_(backend) {}

RenderWorker::~RenderWorker() {
    stop();
}

QString RenderWorker::start() {
    device_ = RenderDevice::open(backend_);
    const QString description = QString::fromStdString(device_->description());
    if (!device_->fallbackReason().empty()) {
        return description + " (" + QString::fromStdString(device_->fallbackReason()) + ")";
    }
    return description;
}

void RenderWorker::stop() {
    loaded_.clear(); // each GL renderer frees its textures in its own context
    device_.reset();
}

RenderWorker::LoadedSeries& RenderWorker::loaded(const std::shared_ptr<const SeriesEntry>& entry) {
    for (auto it = loaded_.begin(); it != loaded_.end(); ++it) {
        if ((*it)->entry == entry) {
            loaded_.splice(loaded_.begin(), loaded_, it);
            return *loaded_.front();
        }
    }
    while (loaded_.size() >= kLoadedSeriesLimit) {
        loaded_.pop_back();
    }
    auto series = std::make_unique<LoadedSeries>();
    series->entry = entry;
    series->volume = std::make_unique<Volume>(loadSeries(*entry));
    // Where GL fails for this series (its shaders, its size), the CPU renders it.
    series->renderer = device_->openRenderer(*series->volume).renderer;
    loaded_.push_front(std::move(series));
    return *loaded_.front();
}

void RenderWorker::render(const RenderJob& job) {
    RenderedFrame frame;
    frame.view = job.view;
    frame.seq = job.seq;
    try {
        LoadedSeries& series = loaded(job.series);
        RenderDescription description = job.description;
        description.volume = series.volume.get();
        const bool interactive = job.quality == Quality::Interactive;
        if (interactive) {
            description = interactiveDescription(description, InteractiveQuality{2.0, job.scale});
        }
        QElapsedTimer timer;
        timer.start();
        const ImageRGBA8 image = series.renderer->render(description).image;
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
        const std::string message = frameMessage(
            header, std::string_view(encoded.constData(), std::size_t(encoded.size())));
        frame.message = QByteArray(message.data(), qsizetype(message.size()));
    } catch (const std::exception& e) {
        frame.error = QString::fromUtf8(e.what());
    }
    emit frameRendered(frame);
}

} // namespace lucent::remote
