#include "server/RenderWorker.h"

#include <QBuffer>
#include <QElapsedTimer>
#include <QImage>
#include <QImageWriter>

#include "core/io/Catalog.h"
#include "core/raycast/CpuRayCaster.h"
#include "render/GlError.h"
#include "render/GpuRayCaster.h"
#include "render/OffscreenContext.h"
#include "protocol/PngEncoder.h"

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

RenderDescription scaledInteractiveDescription(const RenderDescription& still, double scale) {
    RenderDescription d = still;
    d.sampling.step *= 2.0;
    d.width = std::max(1, int(still.width * scale));
    d.height = std::max(1, int(still.height * scale));
    return d;
}

struct RenderWorker::LoadedSeries {
    std::shared_ptr<const SeriesEntry> entry; // held: its address identifies it
    std::unique_ptr<Volume> volume;
    std::unique_ptr<GpuRayCaster> gpu;
    std::unique_ptr<CpuRayCaster> cpu;
};

RenderWorker::RenderWorker(Backend backend) : backend_(backend) {}

RenderWorker::~RenderWorker() {
    stop();
}

QString RenderWorker::start() {
    QString description = "cpu";
    if (backend_ == Backend::Gl) {
        try {
            context_ = OffscreenContext::create();
            description = "gl: " + QString::fromStdString(context_->description());
        } catch (const GlError& e) {
            backend_ = Backend::Cpu;
            description = "cpu (the GL backend is not available: " + QString(e.what()) + ")";
        }
    }
    return description;
}

void RenderWorker::stop() {
    if (context_) {
        context_->makeCurrent();
    }
    loaded_.clear();
    context_.reset();
}

RenderWorker::LoadedSeries& RenderWorker::loaded(const std::shared_ptr<const SeriesEntry>& entry) {
    for (auto it = loaded_.begin(); it != loaded_.end(); ++it) {
        if ((*it)->entry == entry) {
            loaded_.splice(loaded_.begin(), loaded_, it);
            return *loaded_.front();
        }
    }
    while (loaded_.size() >= kLoadedSeriesLimit) {
        loaded_.pop_back(); // frees its GPU resources first: the context is current here
    }
    auto series = std::make_unique<LoadedSeries>();
    series->entry = entry;
    series->volume = std::make_unique<Volume>(loadSeries(*entry));
    if (context_) {
        try {
            series->gpu = std::make_unique<GpuRayCaster>(*series->volume);
        } catch (const GlError&) {
            series->gpu.reset(); // the CPU renders this series
        }
    }
    if (!series->gpu) {
        series->cpu = std::make_unique<CpuRayCaster>(*series->volume);
    }
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
            description = scaledInteractiveDescription(description, job.scale);
        }
        QElapsedTimer timer;
        timer.start();
        const ImageRGBA8 image = series.gpu ? series.gpu->render(description).frame.image
                                            : series.cpu->render(description).image;
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
