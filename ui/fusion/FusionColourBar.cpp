#include "ui/fusion/FusionColourBar.h"

#include <QFontMetrics>
#include <QPainter>

namespace lucent {

QString colourBarLabel(double value) {
    return QString::number(value, 'g', 4);
}

void paintFusionColourBar(QPainter& painter, const QRect& area, const FusionStyle& style,
                          const QString& unit) {
    if (area.height() < 24 || area.width() < 16) {
        return;
    }
    constexpr int kBarWidth = 12;
    const QRect bar(area.right() - kBarWidth + 1, area.top(), kBarWidth, area.height());
    const ColourLut& lut = colourLut(style.colourMap);
    QImage strip(1, 256, QImage::Format_RGB32);
    for (int i = 0; i < 256; ++i) {
        const auto& c = lut[255 - i]; // the high end at the top
        strip.setPixel(0, i, qRgb(c[0], c[1], c[2]));
    }
    painter.save();
    painter.drawImage(bar, strip);
    painter.setPen(QColor(220, 220, 220));
    painter.drawRect(bar.adjusted(0, 0, -1, -1));
    const double low = style.center - 0.5 * style.width;
    const double high = style.center + 0.5 * style.width;
    const QFontMetrics metrics(painter.font());
    const auto label = [&](double value, int y, const QString& suffix) {
        const QString text = colourBarLabel(value) + suffix;
        const int x = bar.left() - 4 - metrics.horizontalAdvance(text);
        painter.drawText(x, y, text);
    };
    const QString unitSuffix = unit.isEmpty() ? QString() : QStringLiteral(" ") + unit;
    label(high, bar.top() + metrics.ascent(), unitSuffix);
    label(style.center, bar.center().y() + metrics.ascent() / 2, QString());
    label(low, bar.bottom(), QString());
    painter.restore();
}

} // namespace lucent
