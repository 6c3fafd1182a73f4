// A render description as JSON (what a distributed server's rank 0 sends the
// other ranks): every field comes back exactly, and a malformed text is
// refused naming the field.
#include <QTest>

#include "core/scene/RenderDescriptionJson.h"

using namespace lucent;

class TestRenderDescriptionJson : public QObject {
    Q_OBJECT

private slots:
    void everyFieldComesBackExactly() {
        RenderDescription d;
        d.transferFunction = loadPreset("ct-bone");
        d.transferFunction.shading.specularPower = 23.25;
        d.camera = {37.123456789012345, -12.5, 1.7, 41.0, 812.3, -3.1, 0.1 + 0.2};
        d.mode = RenderMode::Isosurface;
        d.isoValue = 217.75;
        d.clip.lo = {1.5, 0.0, 7.25};
        d.clip.hi = {40.0, 31.0 / 3.0, 1e9};
        d.sampling = {0.3,
                      Interpolation::Cubic,
                      Classification::Pre,
                      true,
                      0.95,
                      16,
                      false,
                      false,
                      false,
                      Precision::Double,
                      false};
        d.width = 333;
        d.height = 97;
        d.background = {0.1, 0.2, 1.0 / 3.0};

        const RenderDescription back = parseRenderDescription(toJson(d));
        QVERIFY(back.volume == nullptr);
        QVERIFY(back.transferFunction == d.transferFunction);
        QCOMPARE(back.camera.azimuth, d.camera.azimuth);
        QCOMPARE(back.camera.elevation, d.camera.elevation);
        QCOMPARE(back.camera.zoom, d.camera.zoom);
        QCOMPARE(back.camera.fieldOfView, d.camera.fieldOfView);
        QCOMPARE(back.camera.distance, d.camera.distance);
        QCOMPARE(back.camera.panRight, d.camera.panRight);
        QCOMPARE(back.camera.panUp, d.camera.panUp);
        QCOMPARE(back.mode, d.mode);
        QCOMPARE(back.isoValue, d.isoValue);
        QVERIFY(back.clip.lo == d.clip.lo && back.clip.hi == d.clip.hi);
        QCOMPARE(back.sampling.step, d.sampling.step);
        QCOMPARE(back.sampling.interpolation, d.sampling.interpolation);
        QCOMPARE(back.sampling.classification, d.sampling.classification);
        QCOMPARE(back.sampling.preintegrate, d.sampling.preintegrate);
        QCOMPARE(back.sampling.earlyTermination, d.sampling.earlyTermination);
        QCOMPARE(back.sampling.brickSize, d.sampling.brickSize);
        QCOMPARE(back.sampling.emptySpaceLeaping, d.sampling.emptySpaceLeaping);
        QCOMPARE(back.sampling.leapDistance, d.sampling.leapDistance);
        QCOMPARE(back.sampling.blockSkipping, d.sampling.blockSkipping);
        QCOMPARE(back.sampling.precision, d.sampling.precision);
        QCOMPARE(back.sampling.simd, d.sampling.simd);
        QCOMPARE(back.width, d.width);
        QCOMPARE(back.height, d.height);
        QVERIFY(back.background == d.background);
        QCOMPARE(toJson(back), toJson(d));
    }

    void shadingOffSurvives() {
        RenderDescription d;
        d.transferFunction = loadPreset("ct-bone");
        d.transferFunction.shading.enabled = false;
        QVERIFY(!parseRenderDescription(toJson(d)).transferFunction.shading.enabled);
    }

    void malformedTextNamesTheField_data() {
        QTest::addColumn<QString>("edit");
        QTest::addColumn<QString>("field");
        QTest::newRow("no clip") << "clip"
                                 << "clip";
        QTest::newRow("no fov") << "fov"
                                << "fov";
        QTest::newRow("no step") << "step"
                                 << "step";
        QTest::newRow("bad step") << "step=-1"
                                  << "step";
        QTest::newRow("no tf") << "tf"
                               << "tf";
    }
    void malformedTextNamesTheField() {
        QFETCH(QString, edit);
        QFETCH(QString, field);
        RenderDescription d;
        d.transferFunction = loadPreset("ct-bone");
        std::string text = toJson(d);
        const std::string key = edit.section('=', 0, 0).toStdString();
        const std::string quoted = "\"" + key + "\":";
        const std::size_t at = text.find(quoted);
        QVERIFY(at != std::string::npos);
        if (edit.contains('=')) {
            const std::size_t valueEnd = text.find_first_of(",}", at + quoted.size());
            text.replace(at + quoted.size(), valueEnd - at - quoted.size(),
                         "\"" + edit.section('=', 1).toStdString() + "\"");
        } else {
            text.replace(at + 1, key.size(), "x" + key); // the key renamed: missing
        }
        try {
            (void)parseRenderDescription(text);
            QFAIL("accepted");
        } catch (const std::invalid_argument& e) {
            QVERIFY2(QString(e.what()).contains(field), e.what());
        }
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, parseRenderDescription("{\"options\": 3"));
    }
};

QTEST_GUILESS_MAIN(TestRenderDescriptionJson)
#include "test_render_description_json.moc"
