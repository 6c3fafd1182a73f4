#include "ui/app/ScreenshotExport.h"

#include <QImageWriter>
#include <QPainter>
#include <QWidget>

#include "ui/volume/VolumeView.h"

namespace lucent {

QImage grabView(QWidget* view) {
    if (auto* volumeView = qobject_cast<VolumeView*>(view)) {
        return volumeView->grabImage();
    }
    return view->grab().toImage();
}

QImage grabArea(QWidget* area) {
    QImage image = area->grab().toImage();
    QPainter painter(&image); // in logical pixels: grab() sets the device pixel ratio
    for (VolumeView* view : area->findChildren<VolumeView*>()) {
        if (view->isVisibleTo(area) && !view->size().isEmpty()) {
            const QRect rect(view->mapTo(area, QPoint(0, 0)), view->size());
            painter.drawImage(rect, view->grabImage());
        }
    }
    return image;
}

bool writePng(const QImage& image, const QString& file, QString* error) {
    QImageWriter writer(file, "png");
    if (image.isNull()) {
        if (error != nullptr) {
            *error = QStringLiteral("the view has no image");
        }
        return false;
    }
    if (!writer.write(image)) {
        if (error != nullptr) {
            *error = writer.errorString();
        }
        return false;
    }
    return true;
}

} // namespace lucent
