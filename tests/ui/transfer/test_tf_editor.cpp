// The transfer-function editor on real widgets: QTest mouse and key events on
// the canvas, the histogram behind it, user presets on disk.
#include <QApplication>
#include <QSignalSpy>
#include <QStandardPaths>
#include <QTest>

#include <cmath>
#include <filesystem>
#include <memory>

#include "core/tf/VolumeHistogram.h"
#include "tests/support/OffscreenPlatform.h"
#include "ui/transfer/TransferFunctionCanvas.h"
#include "ui/transfer/TransferFunctionEditor.h"

using namespace lucent;

namespace {

// int16 values 0..9 along i (dims 10 x 3 x 2: six of each), then voxel (0,0,0)
// set to 9: value 0 five times, 9 seven times, the others six times.
std::shared_ptr<Volume> makeStepVolume() {
    VolumeGeometry g;
    g.dims = {10, 3, 2};
    auto volume = std::make_shared<Volume>(g, VoxelType::Int16);
    auto voxels = volume->voxels<std::int16_t>();
    for (int k = 0; k < 2; ++k) {
        for (int j = 0; j < 3; ++j) {
            for (int i = 0; i < 10; ++i) {
                voxels[volume->linearIndex(i, j, k)] = static_cast<std::int16_t>(i);
            }
        }
    }
    voxels[0] = 9;
    return volume;
}

// Opacity points at 0, 100 and 200; one white colour stop; values 0..200.
TransferFunction threePoints() {
    TransferFunction tf;
    tf.name = "three";
    tf.opacity = {{0.0, 0.0}, {100.0, 0.5}, {200.0, 1.0}};
    tf.colour = {{0.0, glm::dvec3(1.0)}};
    return tf;
}

} // namespace

class TestTfEditor : public QObject {
    Q_OBJECT

private slots:
    void initTestCase();
    void histogramCountsMatchVolume();
    void dragMovesPointByMousePixels();
    void doubleClickAddsAndDeleteRemoves();
    void rightClickRemovesPoint();
    void colourStripAddsStop();
    void editorForwardsDragsAndSavesPresets();

private:
    // A canvas whose opacity area is exactly 400 x 200 pixels at (8, 8):
    // 0.5 value units and 0.005 opacity per pixel for threePoints().
    std::unique_ptr<TransferFunctionCanvas> makeCanvas();
};

void TestTfEditor::initTestCase() {
    QStandardPaths::setTestModeEnabled(true);
}

std::unique_ptr<TransferFunctionCanvas> TestTfEditor::makeCanvas() {
    auto canvas = std::make_unique<TransferFunctionCanvas>();
    canvas->setTransferFunction(threePoints());
    canvas->resize(416, 240);
    canvas->show();
    if (!QTest::qWaitForWindowExposed(canvas.get())) {
        qWarning("canvas not exposed");
    }
    return canvas;
}

void TestTfEditor::histogramCountsMatchVolume() {
    const auto volume = makeStepVolume();
    const VolumeHistogram h = computeHistogram(*volume, 10);
    QCOMPARE(h.lo, 0.0);
    QCOMPARE(h.hi, 9.0);
    const std::uint64_t expected[10] = {5, 6, 6, 6, 6, 6, 6, 6, 6, 7};
    for (int n = 0; n < 10; ++n) {
        QCOMPARE(h.counts[static_cast<std::size_t>(n)], expected[n]);
    }
    // The editor's own (256 bins): each value's bin holds its count, the rest nothing.
    TransferFunctionEditor editor;
    editor.setVolume(volume);
    const VolumeHistogram& shown = editor.canvas()->histogram();
    QCOMPARE(shown.counts.size(), std::size_t(256));
    std::uint64_t total = 0;
    for (int v = 0; v < 10; ++v) {
        QCOMPARE(shown.counts[static_cast<std::size_t>(shown.binOf(v))], expected[v]);
        total += shown.counts[static_cast<std::size_t>(shown.binOf(v))];
    }
    std::uint64_t all = 0;
    for (const auto c : shown.counts) {
        all += c;
    }
    QCOMPARE(all, total);
    QCOMPARE(all, std::uint64_t(60));
}

void TestTfEditor::dragMovesPointByMousePixels() {
    auto canvas = makeCanvas();
    QCOMPARE(canvas->opacityArea(), QRectF(8, 8, 400, 200));
    const QPoint start = canvas->opacityPointPosition(1).toPoint();
    QCOMPARE(start, QPoint(208, 108));
    QSignalSpy spy(canvas.get(), &TransferFunctionCanvas::transferFunctionChanged);
    QTest::mousePress(canvas.get(), Qt::LeftButton, {}, start);
    QTest::mouseMove(canvas.get(), start + QPoint(20, -10));
    QTest::mouseMove(canvas.get(), start + QPoint(40, -20));
    QTest::mouseRelease(canvas.get(), Qt::LeftButton, {}, start + QPoint(40, -20));
    QCOMPARE(spy.count(), 2); // live while dragging
    const auto& p = canvas->transferFunction().opacity;
    QCOMPARE(p.size(), std::size_t(3));
    QVERIFY2(std::abs(p[1].value - 120.0) < 1e-9, qPrintable(QString::number(p[1].value)));
    QVERIFY2(std::abs(p[1].opacity - 0.6) < 1e-9, qPrintable(QString::number(p[1].opacity)));
    const auto emitted = spy.last().at(0).value<TransferFunction>();
    QCOMPARE(emitted, canvas->transferFunction());
    // The neighbours are untouched, and a drag cannot pass them.
    QCOMPARE(p[0], (OpacityPoint{0.0, 0.0}));
    QTest::mousePress(canvas.get(), Qt::LeftButton, {}, start + QPoint(40, -20));
    QTest::mouseMove(canvas.get(), QPoint(400, 300));
    QTest::mouseRelease(canvas.get(), Qt::LeftButton, {}, QPoint(400, 300));
    QVERIFY(p[1].value < p[2].value);
    QCOMPARE(p[1].opacity, 0.0);
    QVERIFY_THROWS_NO_EXCEPTION(canvas->transferFunction().validate());
}

void TestTfEditor::doubleClickAddsAndDeleteRemoves() {
    auto canvas = makeCanvas();
    QSignalSpy spy(canvas.get(), &TransferFunctionCanvas::transferFunctionChanged);
    // value 50 at x = 8 + 100, opacity 0.8 at y = 208 - 160
    QTest::mouseDClick(canvas.get(), Qt::LeftButton, {}, QPoint(108, 48));
    QCOMPARE(spy.count(), 1);
    auto p = canvas->transferFunction().opacity;
    QCOMPARE(p.size(), std::size_t(4));
    QCOMPARE(p[1].value, 50.0);
    QVERIFY(std::abs(p[1].opacity - 0.8) < 1e-9);
    QCOMPARE(canvas->selectedOpacityPoint(), 1);

    canvas->setFocus();
    QTest::keyClick(canvas.get(), Qt::Key_Delete);
    QCOMPARE(spy.count(), 2);
    QCOMPARE(canvas->transferFunction().opacity, threePoints().opacity);
}

void TestTfEditor::rightClickRemovesPoint() {
    auto canvas = makeCanvas();
    QSignalSpy spy(canvas.get(), &TransferFunctionCanvas::transferFunctionChanged);
    QTest::mouseClick(canvas.get(), Qt::RightButton, {}, canvas->opacityPointPosition(2).toPoint());
    QCOMPARE(spy.count(), 1);
    const auto& p = canvas->transferFunction().opacity;
    QCOMPARE(p.size(), std::size_t(2));
    QCOMPARE(p.back().value, 100.0);
    // A right-click on empty space does nothing.
    QTest::mouseClick(canvas.get(), Qt::RightButton, {}, QPoint(300, 30));
    QCOMPARE(spy.count(), 1);
}

void TestTfEditor::colourStripAddsStop() {
    auto canvas = makeCanvas();
    canvas->setColourPicker([](const QColor&) { return std::optional<QColor>(QColor(255, 0, 0)); });
    QSignalSpy spy(canvas.get(), &TransferFunctionCanvas::transferFunctionChanged);
    const int y = static_cast<int>(canvas->colourStrip().center().y());
    QTest::mouseDClick(canvas.get(), Qt::LeftButton, {}, QPoint(308, y)); // value 150
    QCOMPARE(spy.count(), 1);
    const auto& c = canvas->transferFunction().colour;
    QCOMPARE(c.size(), std::size_t(2));
    QCOMPARE(c[1].value, 150.0);
    QCOMPARE(c[1].rgb, glm::dvec3(1.0, 0.0, 0.0));
    // A cancelled picker changes nothing.
    canvas->setColourPicker([](const QColor&) { return std::optional<QColor>(); });
    QTest::mouseDClick(canvas.get(), Qt::LeftButton, {}, QPoint(58, y));
    QCOMPARE(spy.count(), 1);
}

void TestTfEditor::editorForwardsDragsAndSavesPresets() {
    std::filesystem::remove_all(TransferFunctionEditor::userPresetDirectory());
    TransferFunctionEditor editor;
    editor.resize(500, 320);
    editor.setTransferFunction(threePoints());
    editor.show();
    QVERIFY(QTest::qWaitForWindowExposed(&editor));
    QSignalSpy spy(&editor, &TransferFunctionEditor::transferFunctionChanged);
    TransferFunctionCanvas* canvas = editor.canvas();
    const QPoint start = canvas->opacityPointPosition(1).toPoint();
    QTest::mousePress(canvas, Qt::LeftButton, {}, start);
    QTest::mouseMove(canvas, start + QPoint(10, 0));
    QTest::mouseRelease(canvas, Qt::LeftButton, {}, start + QPoint(10, 0));
    QCOMPARE(spy.count(), 1);
    QVERIFY(editor.transferFunction().opacity[1].value > 100.0);

    QVERIFY(editor.saveUserPreset("my-preset"));
    const auto file = TransferFunctionEditor::userPresetDirectory() / "my-preset.json";
    QVERIFY(std::filesystem::exists(file));
    TransferFunction saved = readTransferFunction(file);
    QCOMPARE(saved.name, std::string("my-preset"));
    QCOMPARE(saved.opacity, editor.transferFunction().opacity);

    QVERIFY(editor.loadPresetNamed("ct-bone"));
    QCOMPARE(spy.count(), 2);
    QCOMPARE(editor.transferFunction(), loadPreset("ct-bone"));
    QVERIFY(editor.loadPresetNamed("my-preset"));
    QCOMPARE(editor.transferFunction().opacity, saved.opacity);
    QVERIFY(!editor.loadPresetNamed("no-such-preset"));
    QVERIFY(!editor.saveUserPreset("../escape"));
    std::filesystem::remove_all(TransferFunctionEditor::userPresetDirectory());
}

int main(int argc, char** argv) {
    lucent::test::useOffscreenPlatform();
    QApplication app(argc, argv);
    TestTfEditor test;
    return QTest::qExec(&test, argc, argv);
}

#include "test_tf_editor.moc"
