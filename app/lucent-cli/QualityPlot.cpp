#include "QualityPlot.h"

#include <QImage>
#include <QPainter>
#include <QPainterPath>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace lucent::cli {

void writeQualityPlot(const std::vector<QualityPoint>& points, const QString& path,
                      const QString& title) {
    constexpr int kW = 900, kH = 600, kLeft = 70, kRight = 20, kTop = 40, kBottom = 60;
    QImage image(kW, kH, QImage::Format_RGB32);
    image.fill(Qt::white);
    QPainter p(&image);
    p.setRenderHint(QPainter::Antialiasing);
    // Identical images have infinite PSNR: drawn at the top of the scale.
    const double yMax = 70.0, yMin = 10.0;
    double msLo = 1e300, msHi = 0.0;
    for (const QualityPoint& q : points) {
        msLo = std::min(msLo, q.ms);
        msHi = std::max(msHi, q.ms);
    }
    msLo = std::max(msLo, 1e-3);
    const double xLo = std::floor(std::log10(msLo)),
                 xHi = std::max(std::ceil(std::log10(msHi)), xLo + 1);
    const auto px = [&](double ms) {
        return kLeft + (std::log10(std::max(ms, 1e-3)) - xLo) / (xHi - xLo) * (kW - kLeft - kRight);
    };
    const auto py = [&](double db) {
        const double v = std::clamp(std::isinf(db) ? yMax : db, yMin, yMax);
        return kTop + (yMax - v) / (yMax - yMin) * (kH - kTop - kBottom);
    };
    p.fillRect(QRectF(QPointF(kLeft, py(40)), QPointF(kW - kRight, py(30))), QColor(210, 240, 210));
    p.setPen(QColor(120, 120, 120));
    for (double d = yMin; d <= yMax; d += 10) {
        p.drawLine(QPointF(kLeft - 4, py(d)), QPointF(kLeft, py(d)));
        p.drawText(QRectF(0, py(d) - 8, kLeft - 8, 16), Qt::AlignRight | Qt::AlignVCenter,
                   QString::number(d));
    }
    for (double e = xLo; e <= xHi; e += 1) {
        const double ms = std::pow(10.0, e);
        p.drawLine(QPointF(px(ms), kH - kBottom), QPointF(px(ms), kH - kBottom + 4));
        p.drawText(QRectF(px(ms) - 40, kH - kBottom + 6, 80, 16), Qt::AlignCenter,
                   QString::number(ms) + " ms");
    }
    p.drawRect(QRectF(QPointF(kLeft, kTop), QPointF(kW - kRight, kH - kBottom)));
    p.setPen(Qt::black);
    p.drawText(QRectF(0, 8, kW, 20), Qt::AlignCenter, title);
    p.drawText(QRectF(0, kH - 28, kW, 20), Qt::AlignCenter,
               "time per frame (log)   |   green: 30-40 dB   |   fronts: red shaded (blue points), "
               "orange unshaded (grey points)");
    p.save();
    p.translate(16, kH / 2.0);
    p.rotate(-90);
    p.drawText(QRectF(-100, -10, 200, 20), Qt::AlignCenter, "PSNR (dB) vs reference");
    p.restore();
    p.setPen(Qt::NoPen);
    for (const QualityPoint& q : points) {
        p.setBrush(q.setting.shading ? QColor(60, 90, 200, 150) : QColor(150, 150, 150, 150));
        p.drawEllipse(QPointF(px(q.ms), py(q.psnrDb)), 3.5, 3.5);
    }
    // One front per shading state: red shaded, orange unshaded.
    for (const bool shading : {true, false}) {
        std::vector<QualityPoint> front;
        std::copy_if(
            points.begin(), points.end(), std::back_inserter(front),
            [&](const QualityPoint& q) { return q.pareto && q.setting.shading == shading; });
        std::sort(front.begin(), front.end(),
                  [](const QualityPoint& a, const QualityPoint& b) { return a.ms < b.ms; });
        QPainterPath line;
        for (std::size_t n = 0; n < front.size(); ++n) {
            const QPointF at(px(front[n].ms), py(front[n].psnrDb));
            n == 0 ? line.moveTo(at) : line.lineTo(at);
        }
        p.setPen(QPen(shading ? QColor(200, 30, 30) : QColor(230, 140, 20), 2));
        p.setBrush(Qt::NoBrush);
        p.drawPath(line);
    }
    p.end();
    if (!image.save(path, "PNG")) {
        throw std::runtime_error("cannot write the plot " + path.toStdString());
    }
}

} // namespace lucent::cli
