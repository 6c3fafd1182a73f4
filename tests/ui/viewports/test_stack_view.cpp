// The 2D stack viewport: frames fitted with their pixel aspect, wheel and keys
// through the frames, cine at the frame time, window/level on grey frames, zoom
// and pan, reset; and a real ultrasound-style cine (a CT coloured and made a
// multi-frame object by DCMTK/GDCM, tests/core/stack/make_stacks.py) shown pixel
// for pixel.
#include <QApplication>
#include <QSignalSpy>
#include <QTest>
#include <QWheelEvent>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>

#include "core/dicom/StackLoader.h"
#include "tests/support/OffscreenPlatform.h"
#include "tests/support/RealData.h"
#include "ui/viewports/StackView.h"

using namespace lucent;

namespace {

// Frame f: pixel (x, y) is colour (40 f + 10 x, 20 y, 200 - 40 f): every pixel and
// frame differ.
std::shared_ptr<ImageStack> colourStack(int columns, int rows, int frames) {
    auto s = std::make_shared<ImageStack>();
    s->columns = columns;
    s->rows = rows;
    s->colour = StackColour::Rgb8;
    s->photometric = "RGB";
    s->description = "test colours";
    for (int f = 0; f < frames; ++f) {
        s->frames.push_back({});
        for (int y = 0; y < rows; ++y) {
            for (int x = 0; x < columns; ++x) {
                s->rgb.push_back(static_cast<std::uint8_t>(40 * f + 10 * x));
                s->rgb.push_back(static_cast<std::uint8_t>(20 * y));
                s->rgb.push_back(static_cast<std::uint8_t>(200 - 40 * f));
            }
        }
    }
    return s;
}

void wheel(QWidget* w, int delta, Qt::KeyboardModifiers modifiers = Qt::NoModifier,
           QPointF pos = {}) {
    if (pos.isNull()) {
        pos = QPointF(w->width() / 2.0, w->height() / 2.0);
    }
    QWheelEvent event(pos, w->mapToGlobal(pos), QPoint(), QPoint(0, delta), Qt::NoButton, modifiers,
                      Qt::NoScrollPhase, false);
    QApplication::sendEvent(w, &event);
}

QRgb colourAt(const StackView& view, int x, int y) {
    return view.image().pixel(x, y);
}

// The widget pixel at the centre of the frame's pixel (i, j).
QPoint centreOf(const StackView& view, int i, int j, int columns, int rows) {
    const QRectF r = view.imageRect();
    return QPointF(r.left() + (i + 0.5) * r.width() / columns,
                   r.top() + (j + 0.5) * r.height() / rows)
        .toPoint();
}

} // namespace

class TestStackView : public QObject {
    Q_OBJECT
private slots:
    void framesFitAndWheelSteps() {
        StackView view;
        view.resize(400, 300);
        view.setStack(colourStack(4, 2, 3));
        // 4x2 square pixels in 400x300: 100 px a pixel, centred vertically.
        QCOMPARE(view.imageRect(), QRectF(0, 50, 400, 200));
        QCOMPARE(colourAt(view, 150, 100), qRgb(10, 0, 200));  // pixel (1, 0) of frame 0
        QCOMPARE(colourAt(view, 350, 200), qRgb(30, 20, 200)); // pixel (3, 1)
        QCOMPARE(colourAt(view, 200, 20), qRgb(0, 0, 0));      // outside: black
        QSignalSpy frames(&view, &StackView::frameChanged);
        wheel(&view, -120); // scrolling down: the next frame
        QCOMPARE(view.frame(), 1);
        QCOMPARE(frames.count(), 1);
        QCOMPARE(frames.at(0).at(0).toInt(), 1);
        QCOMPARE(colourAt(view, 150, 100), qRgb(50, 0, 160));
        wheel(&view, -240);
        QCOMPARE(view.frame(), 2); // clamped at the last frame
        wheel(&view, 120);
        QCOMPARE(view.frame(), 1);
        QTest::keyClick(&view, Qt::Key_Home);
        QCOMPARE(view.frame(), 0);
        view.setFrame(7);
        QCOMPARE(view.frame(), 2);
    }

    void pixelAspectIsKept() {
        auto s = colourStack(4, 2, 1);
        s->frames[0].hasPixelSpacing = true;
        s->frames[0].pixelSpacing = {0.5, 1.0}; // pixels twice as tall as wide
        StackView view;
        view.resize(400, 300);
        view.setStack(s);
        // 2 mm x 2 mm: a square, 300 px on a side, centred.
        QCOMPARE(view.imageRect(), QRectF(50, 0, 300, 300));
    }

    void zoomPanAndReset() {
        StackView view;
        view.resize(400, 300);
        view.setStack(colourStack(4, 2, 1));
        const QPoint anchor = centreOf(view, 3, 1, 4, 2);
        wheel(&view, 120, Qt::ControlModifier, anchor);
        QCOMPARE(view.zoom(), StackView::zoomStepFactor());
        // The pixel under the mouse stays under it.
        QCOMPARE(colourAt(view, anchor.x(), anchor.y()), qRgb(30, 20, 200));
        QCOMPARE(view.imageRect().width(), 500.0);
        const QRectF before = view.imageRect();
        QTest::mousePress(&view, Qt::MiddleButton, Qt::NoModifier, QPoint(200, 150));
        QTest::mouseMove(&view, QPoint(170, 160));
        QTest::mouseRelease(&view, Qt::MiddleButton, Qt::NoModifier, QPoint(170, 160));
        QCOMPARE(view.imageRect().topLeft(), before.topLeft() + QPointF(-30, 10));
        QTest::keyClick(&view, Qt::Key_R);
        QCOMPARE(view.zoom(), 1.0);
        QCOMPARE(view.imageRect(), QRectF(0, 50, 400, 200));
    }

    void rightDragWindowsGreyFrames() {
        auto s = std::make_shared<ImageStack>();
        s->columns = 2;
        s->rows = 1;
        s->grey = {0.0f, 1000.0f};
        s->frames.resize(1);
        s->window = {500.0, 1000.0};
        s->photometric = "MONOCHROME2";
        StackView view;
        view.resize(200, 100);
        view.setStack(s);
        QCOMPARE(qGray(colourAt(view, 50, 50)), 0);
        QCOMPARE(qGray(colourAt(view, 150, 50)), 255);
        QSignalSpy windows(&view, &StackView::windowChanged);
        // Down = higher level: the bright pixel dims. Right = wider.
        QTest::mousePress(&view, Qt::RightButton, Qt::NoModifier, QPoint(100, 20));
        QTest::mouseMove(&view, QPoint(150, 70));
        QTest::mouseRelease(&view, Qt::RightButton, Qt::NoModifier, QPoint(150, 70));
        QVERIFY(windows.count() > 0);
        QCOMPARE(view.window().centre, 500.0 + 50 * 1.0); // range 1000: 1 unit a pixel
        QCOMPARE(view.window().width, 1000.0 + 50 * 1.0);
        QVERIFY(qGray(colourAt(view, 150, 50)) < 255);
        // MONOCHROME1: the same values shown the other way round.
        auto inverted = std::make_shared<ImageStack>(*s);
        inverted->inverted = true;
        view.setStack(inverted);
        QCOMPARE(qGray(colourAt(view, 50, 50)), 255);
        QCOMPARE(qGray(colourAt(view, 150, 50)), 0);
        QTest::keyClick(&view, Qt::Key_R);
        QCOMPARE(view.window().centre, 500.0);
    }

    void cineRunsAtTheFrameTime() {
        auto s = colourStack(4, 2, 5);
        s->frameTimeMs = 20.0;
        StackView view;
        view.resize(200, 100);
        view.setStack(s);
        QSignalSpy frames(&view, &StackView::frameChanged);
        QTest::keyClick(&view, Qt::Key_C);
        QVERIFY(view.cineRunning());
        QTRY_VERIFY_WITH_TIMEOUT(frames.count() >= 6, 2000); // wrapped past the last frame
        QTest::keyClick(&view, Qt::Key_C);
        QVERIFY(!view.cineRunning());
        const int stopped = view.frame();
        QTest::qWait(100);
        QCOMPARE(view.frame(), stopped);
        // Without a frame time: 10 fps.
        QCOMPARE(colourStack(1, 1, 2)->cineIntervalMs(), 100.0);
    }

    void realCineShownPixelForPixel() {
        REQUIRE_DATA("dcm_qa_ct/Philips_S21570/S2010");
        const std::filesystem::path folder = std::filesystem::path(LUCENT_STACKS_DIR) / "us_cine";
        QVERIFY2(std::filesystem::exists(folder), "make_stacks.py made no us_cine");
        const Catalog c = scanPath(folder);
        QCOMPARE(c.series.size(), std::size_t(1));
        auto stack = std::make_shared<const ImageStack>(loadStack(c.series.front()));
        std::ifstream in(std::filesystem::path(LUCENT_STACKS_DIR) / "cine_rgb.raw",
                         std::ios::binary);
        const std::vector<unsigned char> source{std::istreambuf_iterator<char>(in),
                                                std::istreambuf_iterator<char>()};
        StackView view;
        view.resize(stack->columns, stack->rows); // one screen pixel a frame pixel
        view.setStack(stack);
        for (int f : {0, 3}) {
            view.setFrame(f);
            const QImage shown = view.image();
            int compared = 0;
            for (int y = 60; y < stack->rows - 60; y += 23) {
                for (int x = 7; x < stack->columns; x += 29) {
                    const std::size_t at =
                        3 * ((std::size_t(f) * stack->rows + y) * stack->columns + x);
                    QCOMPARE(shown.pixel(x, y), qRgb(source[at], source[at + 1], source[at + 2]));
                    ++compared;
                }
            }
            QVERIFY(compared > 200);
        }
    }
};

int main(int argc, char** argv) {
    lucent::test::useOffscreenPlatform();
    QApplication app(argc, argv);
    TestStackView test;
    return QTest::qExec(&test, argc, argv);
}

#include "test_stack_view.moc"
