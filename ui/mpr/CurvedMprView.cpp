#include "ui/mpr/CurvedMprView.h"

#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QMouseEvent>
#include <QPainter>
#include <QSpinBox>
#include <QVBoxLayout>

#include <algorithm>
#include <functional>

#include "ui/mpr/MprCursor.h"
#include "ui/mpr/SliceOverlay.h"

namespace lucent {

// An image drawn to fit with its aspect kept (its pixels are square in mm),
// a scale bar, an optional horizontal cursor row, and mouse rows reported.
class CurvedImagePane : public QWidget {
public:
    explicit CurvedImagePane(QWidget* parent) : QWidget(parent) { setMouseTracking(true); }
    void show(const QImage& image, double pixelSize, int cursorRow) {
        image_ = image;
        pixelSize_ = pixelSize;
        cursorRow_ = cursorRow;
        update();
    }
    std::function<void(int row)> onRow;
    QSize sizeHint() const override { return {360, 480}; }

protected:
    void paintEvent(QPaintEvent*) override {
        QPainter painter(this);
        painter.fillRect(rect(), Qt::black);
        if (image_.isNull()) {
            return;
        }
        const QRectF target = fitted();
        painter.drawImage(target, image_);
        const double scale = target.width() / image_.width();
        if (cursorRow_ >= 0) {
            const double y = target.top() + (cursorRow_ + 0.5) * scale;
            painter.setPen(QPen(QColor(80, 200, 255), 1.0));
            painter.drawLine(QPointF(target.left(), y), QPointF(target.right(), y));
        }
        paintScaleBar(painter, target.toRect(), pixelSize_ / scale);
    }
    void mouseMoveEvent(QMouseEvent* event) override {
        const QRectF target = fitted();
        if (!onRow || image_.isNull() || !target.contains(event->position())) {
            return;
        }
        onRow(int((event->position().y() - target.top()) / target.height() * image_.height()));
    }
    void mousePressEvent(QMouseEvent* event) override { mouseMoveEvent(event); }

private:
    QRectF fitted() const {
        const double scale =
            std::min(width() / double(image_.width()), height() / double(image_.height()));
        const QSizeF size(image_.width() * scale, image_.height() * scale);
        return {QPointF((width() - size.width()) / 2, (height() - size.height()) / 2), size};
    }
    QImage image_;
    double pixelSize_ = 1.0;
    int cursorRow_ = -1;
};

CurvedMprView::CurvedMprView(MprCursor* cursor, QWidget* parent)
    : QWidget(parent), cursor_(cursor), kind_(new QComboBox(this)), rotation_(new QSpinBox(this)),
      slab_(new QDoubleSpinBox(this)), slabMode_(new QComboBox(this)),
      curved_(new CurvedImagePane(this)), across_(new CurvedImagePane(this)) {
    setWindowTitle(tr("Curved MPR"));
    kind_->addItems({tr("Straightened"), tr("Stretched")});
    rotation_->setRange(-180, 180);
    rotation_->setSuffix(QStringLiteral(" deg"));
    rotation_->setWrapping(true);
    slab_->setRange(0.0, 50.0);
    slab_->setSuffix(QStringLiteral(" mm"));
    slab_->setSpecialValueText(tr("thin"));
    slabMode_->addItems({QStringLiteral("MIP"), QStringLiteral("MinIP"), tr("Average")});
    auto* controls = new QFormLayout;
    controls->addRow(tr("Reformation"), kind_);
    controls->addRow(tr("Turn"), rotation_);
    controls->addRow(tr("Slab"), slab_);
    controls->addRow(tr("Slab mode"), slabMode_);
    auto* side = new QVBoxLayout;
    side->addLayout(controls);
    side->addWidget(across_, 1);
    auto* layout = new QHBoxLayout(this);
    layout->addWidget(curved_, 2);
    layout->addLayout(side, 1);
    curved_->onRow = [this](int row) { setArcFromRow(row); };
    connect(kind_, &QComboBox::currentIndexChanged, this, [this] { rebuild(); });
    connect(rotation_, &QSpinBox::valueChanged, this, [this] { rebuild(); });
    connect(slab_, &QDoubleSpinBox::valueChanged, this, [this] { rebuild(); });
    connect(slabMode_, &QComboBox::currentIndexChanged, this, [this] { rebuild(); });
    connect(cursor_, &MprCursor::windowChanged, this, [this] {
        grey_ = reformationImage();
        setArc(arc_);
    });
}

CurvedMprView::~CurvedMprView() = default;

void CurvedMprView::setPath(std::shared_ptr<const Volume> volume,
                            const std::vector<glm::dvec3>& points, const glm::dvec3& up) {
    if (!volume || volume->empty()) {
        throw std::invalid_argument("curved MPR: no volume is loaded");
    }
    const glm::dvec3 spacing = volume->geometry().spacing;
    pixelSize_ = std::min({spacing.x, spacing.y, spacing.z});
    Centerline line = centerlineThrough(points, pixelSize_, up);
    volume_ = std::move(volume);
    centerline_ = std::move(line);
    up_ = up;
    arc_ = 0.5 * centerline_.length();
    rebuild();
}

void CurvedMprView::setKind(Kind kind) {
    kind_->setCurrentIndex(kind == Kind::Straightened ? 0 : 1);
}

void CurvedMprView::setRotation(double degrees) {
    rotation_->setValue(int(std::lround(degrees)));
}

void CurvedMprView::setSlab(double thicknessMm, SlabMode mode) {
    const QSignalBlocker block(slab_);
    slab_->setValue(thicknessMm);
    slabMode_->setCurrentIndex(int(mode));
    rebuild();
}

void CurvedMprView::rebuild() {
    if (!volume_) {
        return;
    }
    CurvedOptions o;
    o.pixelSize = pixelSize_;
    o.halfWidth = 40.0;
    o.rotationDeg = rotation_->value();
    o.slabThickness = slab_->value();
    o.slabMode = SlabMode(slabMode_->currentIndex());
    const bool straight = kind_->currentIndex() == 0;
    rotation_->setEnabled(straight);
    try {
        reformation_ = straight ? straightenedReformat(*volume_, centerline_, o)
                                : stretchedReformat(*volume_, centerline_, up_, o);
    } catch (const std::invalid_argument&) {
        // A path drawn along the view's normal cannot be stretched: show it straightened.
        kind_->setCurrentIndex(0);
        return;
    }
    grey_ = reformationImage(); // once per reformation and window, not per mouse move
    setArc(arc_);
}

void CurvedMprView::setArcFromRow(int row) {
    if (row >= 0 && row < int(reformation_.rowArc.size())) {
        setArc(reformation_.rowArc[std::size_t(row)]);
        cursor_->setPoint(centerline_.pointAt(arc_));
    }
}

void CurvedMprView::setArc(double s) {
    arc_ = std::clamp(s, 0.0, centerline_.length());
    updateCrossSection();
    // The row whose arc is nearest: rows are at increasing arc lengths.
    const auto& arcs = reformation_.rowArc;
    const auto at = std::lower_bound(arcs.begin(), arcs.end(), arc_);
    const int row =
        arcs.empty() ? -1 : int(std::min(at - arcs.begin(), std::ptrdiff_t(arcs.size() - 1)));
    curved_->show(grey_, reformation_.pixelSize, row);
    across_->show(crossSectionImage(), pixelSize_, -1);
}

void CurvedMprView::updateCrossSection() {
    if (volume_) {
        crossSection_ =
            sampleImage(*volume_, crossSection(centerline_, arc_, crossSize_, pixelSize_));
    }
}

QImage CurvedMprView::toGrey(const std::vector<float>& values, int width, int height) const {
    QImage image(width, height, QImage::Format_Grayscale8);
    for (int y = 0; y < height; ++y) {
        uchar* line = image.scanLine(y);
        for (int x = 0; x < width; ++x) {
            const std::uint8_t grey = windowToGrey(values[std::size_t(y) * width + x],
                                                   cursor_->windowCenter(), cursor_->windowWidth());
            line[x] = cursor_->invertedGrey() ? static_cast<uchar>(255 - grey) : grey;
        }
    }
    return image;
}

QImage CurvedMprView::reformationImage() const {
    return toGrey(reformation_.pixels, reformation_.width, reformation_.height);
}

QImage CurvedMprView::crossSectionImage() const {
    return crossSection_.empty() ? QImage() : toGrey(crossSection_, crossSize_, crossSize_);
}

} // namespace lucent
