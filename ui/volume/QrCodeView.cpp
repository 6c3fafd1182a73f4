#include "ui/volume/QrCodeView.h"

#include <QImage>
#include <QPainter>

#include <algorithm>

namespace lucent {

QrCodeView::QrCodeView(QWidget* parent) : QWidget(parent) {
    setMinimumSize(160, 160);
    setSizePolicy(QSizePolicy::Expanding, QSizePolicy::Expanding);
}

void QrCodeView::setCode(const remote::QrCode& code) {
    code_ = code;
    update();
}

QImage QrCodeView::image(int scale) const {
    if (code_.size == 0) {
        return {};
    }
    const int modules = code_.size + 2 * remote::kQrQuietZone;
    QImage out(modules * scale, modules * scale, QImage::Format_Grayscale8);
    out.fill(Qt::white);
    QPainter painter(&out);
    for (int y = 0; y < code_.size; ++y) {
        for (int x = 0; x < code_.size; ++x) {
            if (code_.dark(x, y)) {
                painter.fillRect((x + remote::kQrQuietZone) * scale,
                                 (y + remote::kQrQuietZone) * scale, scale, scale, Qt::black);
            }
        }
    }
    return out;
}

QSize QrCodeView::sizeHint() const {
    return {320, 320};
}

void QrCodeView::paintEvent(QPaintEvent*) {
    if (code_.size == 0) {
        return;
    }
    const int modules = code_.size + 2 * remote::kQrQuietZone;
    const int scale = std::max(1, std::min(width(), height()) / modules);
    const QImage drawn = image(scale);
    QPainter painter(this);
    painter.drawImage((width() - drawn.width()) / 2, (height() - drawn.height()) / 2, drawn);
}

} // namespace lucent
