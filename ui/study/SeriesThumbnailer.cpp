#include "ui/study/SeriesThumbnailer.h"

#include <QPointer>

#include "core/dicom/StackLoader.h"
#include "core/io/Catalog.h"
#include "core/io/SeriesPreview.h"
#include "core/stack/StackRendering.h"
#include "ui/study/StudyBrowser.h"

namespace lucent {

namespace {

// A colour or cine series: its middle frame through its own window.
QImage stackThumbnail(const SeriesEntry& entry, const LoadControl& control, int size) {
    const ImageStack stack = loadStackPreview(entry, control);
    const ImageRGBA8 frame = renderStackFrame(stack, 0, stack.defaultWindow());
    const QImage rgba(frame.pixels.data(), frame.width, frame.height, QImage::Format_RGBA8888);
    return rgba.scaled(size, size, Qt::KeepAspectRatio, Qt::SmoothTransformation);
}

} // namespace

SeriesThumbnailer::SeriesThumbnailer(int size, QObject* parent) : QObject(parent), size_(size) {
    pool_.setMaxThreadCount(1);
}

SeriesThumbnailer::~SeriesThumbnailer() {
    stop_.request_stop();
    pool_.clear();
    pool_.waitForDone();
}

void SeriesThumbnailer::remember(const QString& path, const QString& seriesUid,
                                 const QImage& image) {
    cache_.insert(key(path, seriesUid), image);
}

void SeriesThumbnailer::request(const QString& path, const QString& seriesUid,
                                std::optional<SeriesEntry> entry) {
    const QString k = key(path, seriesUid);
    if (const auto hit = cache_.constFind(k); hit != cache_.constEnd()) {
        emit thumbnailReady(path, seriesUid, *hit);
        return;
    }
    if (asked_.value(k)) {
        return; // on its way
    }
    asked_.insert(k, true);
    ++pending_;
    const QPointer<SeriesThumbnailer> self(this);
    const int size = size_;
    const std::stop_token stop = stop_.get_token();
    pool_.start([self, path, seriesUid, entry = std::move(entry), size, stop] {
        QImage image;
        QString error;
        try {
            LoadControl control;
            control.stop = stop;
            control.threads = 1;
            std::optional<SeriesEntry> e = entry;
            if (!e) {
                const Catalog catalog = scanPath(path.toStdString(), control);
                const SeriesEntry* found = seriesUid.isEmpty()
                                               ? catalog.defaultEntry()
                                               : catalog.find(seriesUid.toStdString());
                if (found == nullptr) {
                    throw LoadError(path.toStdString() + " holds no series " +
                                    seriesUid.toStdString());
                }
                e = *found;
            }
            if (e->kind == SeriesKind::Stack) {
                image = stackThumbnail(*e, control, size);
            } else {
                Volume preview = loadPreviewImage(*e, control);
                if (e->kind == SeriesKind::Localizer) {
                    // A scout's values are projections, not HU: window it by its own
                    // percentiles (what defaultWindow does for non-CT data).
                    preview.modality.clear();
                }
                image = StudyBrowser::thumbnail(preview, size);
            }
        } catch (const LoadCancelled&) {
            return;
        } catch (const std::exception& ex) {
            error = QString::fromStdString(ex.what());
        }
        QMetaObject::invokeMethod(
            self,
            [self, path, seriesUid, image, error] {
                if (self) {
                    self->finish(path, seriesUid, image, error);
                }
            },
            Qt::QueuedConnection);
    });
}

void SeriesThumbnailer::finish(const QString& path, const QString& seriesUid, const QImage& image,
                               const QString& error) {
    --pending_;
    asked_.remove(key(path, seriesUid));
    if (!error.isEmpty()) {
        emit thumbnailFailed(path, seriesUid, error);
        return;
    }
    cache_.insert(key(path, seriesUid), image);
    emit thumbnailReady(path, seriesUid, image);
}

} // namespace lucent
