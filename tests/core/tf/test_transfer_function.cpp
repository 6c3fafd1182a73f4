// Transfer functions: interpolation, the brick empty-space test, the JSON format and
// its errors, presets, the baked table, and pre-integration against a brute-force
// integral.
#include <QTemporaryDir>
#include <QTest>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <utility>

#include "core/tf/TransferFunction.h"

using namespace lucent;

namespace {

TransferFunction sample() {
    TransferFunction tf;
    tf.name = "sample";
    tf.modality = "CT";
    tf.opacity = {{0.0, 0.0}, {100.0, 0.5}, {200.0, 0.2}};
    tf.colour = {{0.0, {1.0, 0.0, 0.0}}, {100.0, {0.0, 1.0, 0.0}}, {300.0, {0.0, 0.0, 1.0}}};
    return tf;
}

// The closed form for a constant value: the corrected sample, premultiplied.
glm::dvec4 closedForm(const TransferFunction& tf, double s, double stepRatio) {
    const double alpha = 1.0 - std::pow(1.0 - tf.opacityAt(s), stepRatio);
    return {tf.colourAt(s) * alpha, alpha};
}

// An independent reference: front-to-back compositing of `steps` midpoint samples,
// each corrected to its length.
glm::dvec4 bruteForce(const TransferFunction& tf, double sf, double sb, double stepRatio,
                      int steps = 100000) {
    glm::dvec3 rgb(0.0);
    double alpha = 0.0;
    for (int k = 0; k < steps; ++k) {
        const double s = sf + (sb - sf) * (k + 0.5) / steps;
        const double a = 1.0 - std::pow(1.0 - tf.opacityAt(s), stepRatio / steps);
        rgb += (1.0 - alpha) * a * tf.colourAt(s);
        alpha += (1.0 - alpha) * a;
    }
    return {rgb, alpha};
}

double maxDifference(const glm::dvec4& a, const glm::dvec4& b) {
    const glm::dvec4 d = glm::abs(a - b);
    return std::max(std::max(d.x, d.y), std::max(d.z, d.w));
}

template <typename Fn> QString errorOf(Fn fn) {
    try {
        fn();
    } catch (const TransferFunctionError& e) {
        return QString::fromStdString(e.what());
    } catch (const std::exception& e) {
        return "wrong exception type: " + QString::fromStdString(e.what());
    }
    return "no error";
}

const QByteArray kValid = R"({"opacity": [[0, 0], [1, 1]], "colour": [[0, 0, 0, 0]]})";

} // namespace

class TestTransferFunction : public QObject {
    Q_OBJECT

private slots:
    void interpolation() {
        const TransferFunction tf = sample();
        QCOMPARE(tf.opacityAt(0.0), 0.0);
        QCOMPARE(tf.opacityAt(100.0), 0.5);
        QCOMPARE(tf.opacityAt(200.0), 0.2);
        QCOMPARE(tf.opacityAt(50.0), 0.25);
        QVERIFY(std::abs(tf.opacityAt(150.0) - 0.35) < 1e-15);
        QCOMPARE(tf.opacityAt(-1e9), 0.0);
        QCOMPARE(tf.opacityAt(1e9), 0.2);
        QVERIFY(tf.colourAt(100.0) == glm::dvec3(0.0, 1.0, 0.0));
        QVERIFY(tf.colourAt(200.0) == glm::dvec3(0.0, 0.5, 0.5));
        QVERIFY(tf.colourAt(-5.0) == glm::dvec3(1.0, 0.0, 0.0));
        QVERIFY(tf.colourAt(400.0) == glm::dvec3(0.0, 0.0, 1.0));
        const TransferFunction empty;
        QCOMPARE(empty.opacityAt(1.0), 0.0);
        QVERIFY(empty.colourAt(1.0) == glm::dvec3(0.0));
    }

    void maxOpacity() {
        const TransferFunction tf = sample();
        QCOMPARE(tf.maxOpacity(50.0, 150.0), 0.5); // the peak at 100 lies inside
        QCOMPARE(tf.maxOpacity(150.0, 50.0), 0.5); // either order
        QCOMPARE(tf.maxOpacity(120.0, 180.0), tf.opacityAt(120.0));
        QCOMPARE(tf.maxOpacity(-50.0, 0.0), 0.0); // the empty-space test
        QCOMPARE(tf.maxOpacity(-50.0, 1e-9), tf.opacityAt(1e-9));
        QCOMPARE(tf.maxOpacity(250.0, 1e6), 0.2);
        QCOMPARE(tf.maxOpacity(100.0, 100.0), 0.5);
        QCOMPARE(tf.maxOpacity(-1e6, 1e6), 0.5);
    }

    void validateNamesField() {
        TransferFunction tf = sample();
        tf.opacity[1].opacity = std::numeric_limits<double>::quiet_NaN();
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, tf.validate());
        try {
            tf.validate();
        } catch (const std::invalid_argument& e) {
            QVERIFY2(QString(e.what()).contains("opacity[1]"), e.what());
        }
        tf = sample();
        tf.colour.clear();
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, tf.validate());
        tf = sample();
        tf.colour[2].value = std::numeric_limits<double>::infinity();
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, tf.validate());
        tf = sample();
        tf.shading.specularPower = -1.0;
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, tf.validate());
    }

    void jsonRoundTrip() {
        TransferFunction tf = sample();
        tf.name = "quote \" and ünïcode";
        tf.opacity[1] = {1.0 / 3.0, 0.1 + 0.2};
        tf.colour[1] = {123.456789012345678, {1e-300, 2.0 / 3.0, 0.7}};
        tf.colour[0].value = -1024.125;
        tf.shading = {false, 0.25, 0.75, 1.0 / 7.0, 42.5};
        const TransferFunction back = parseTransferFunction(toJson(tf), "memory");
        QVERIFY(back == tf);

        const QTemporaryDir dir;
        const std::filesystem::path file = dir.filePath("tf.json").toStdString();
        writeTransferFunction(tf, file);
        QVERIFY(readTransferFunction(file) == tf);
        QVERIFY(!std::filesystem::exists(file.string() + ".tmp"));

        // Optional keys take their defaults.
        const TransferFunction minimal = parseTransferFunction(kValid.toStdString(), "min");
        QVERIFY(minimal.shading == Shading{});
        QVERIFY(minimal.name.empty() && minimal.modality.empty());
    }

    void errors_data() {
        QTest::addColumn<QByteArray>("json");
        QTest::addColumn<QString>("field");
        QTest::newRow("malformed") << QByteArray(R"({"opacity": [[0, 0]])") << "malformed JSON";
        QTest::newRow("empty file") << QByteArray("") << "malformed JSON";
        QTest::newRow("not an object") << QByteArray("[1, 2]") << "top level";
        QTest::newRow("missing opacity")
            << QByteArray(R"({"colour": [[0, 0, 0, 0]]})") << "'opacity': missing";
        QTest::newRow("missing colour")
            << QByteArray(R"({"opacity": [[0, 0]]})") << "'colour': missing";
        QTest::newRow("empty opacity")
            << QByteArray(R"({"opacity": [], "colour": [[0, 0, 0, 0]]})") << "'opacity'";
        QTest::newRow("unsorted")
            << QByteArray(R"({"opacity": [[0, 0], [5, 1], [2, 0]], "colour": [[0, 0, 0, 0]]})")
            << "'opacity[2]'";
        QTest::newRow("duplicate")
            << QByteArray(R"({"opacity": [[0, 0]], "colour": [[0, 0, 0, 0], [0, 1, 1, 1]]})")
            << "'colour[1]'";
        QTest::newRow("opacity 1.5")
            << QByteArray(R"({"opacity": [[0, 0], [1, 1.5]], "colour": [[0, 0, 0, 0]]})")
            << "'opacity[1]': opacity 1.5 is outside [0, 1]";
        QTest::newRow("rgb below 0")
            << QByteArray(R"({"opacity": [[0, 0]], "colour": [[0, 0, -0.1, 0]]})")
            << "'colour[0]': green";
        QTest::newRow("unknown key") << QByteArray(R"({"opacity": [[0, 0]], "color": []})")
                                     << "'color': unknown key (did you mean 'colour'?)";
        QTest::newRow("unknown shading key")
            << QByteArray(R"({"opacity": [[0, 0]], "colour": [[0, 0, 0, 0]],
                             "shading": {"specularPower": 3}})")
            << "'shading.specularPower': unknown key";
        QTest::newRow("string for number")
            << QByteArray(R"({"opacity": [[0, "0.5"]], "colour": [[0, 0, 0, 0]]})")
            << "'opacity[0]': expected a number, got string";
        QTest::newRow("short point")
            << QByteArray(R"({"opacity": [[0, 0]], "colour": [[0, 0, 0]]})") << "'colour[0]'";
        QTest::newRow("name not a string")
            << QByteArray(R"({"name": 3, "opacity": [[0, 0]], "colour": [[0, 0, 0, 0]]})")
            << "'name'";
        QTest::newRow("modality")
            << QByteArray(R"({"modality": "PT", "opacity": [[0, 0]], "colour": [[0, 0, 0, 0]]})")
            << "'modality'";
        QTest::newRow("enabled not bool")
            << QByteArray(R"({"opacity": [[0, 0]], "colour": [[0, 0, 0, 0]],
                             "shading": {"enabled": 1}})")
            << "'shading.enabled'";
        QTest::newRow("negative ambient")
            << QByteArray(R"({"opacity": [[0, 0]], "colour": [[0, 0, 0, 0]],
                             "shading": {"ambient": -0.5}})")
            << "'shading.ambient'";
    }

    void errors() {
        QFETCH(QByteArray, json);
        QFETCH(QString, field);
        const QString message =
            errorOf([&] { parseTransferFunction(json.toStdString(), "my.json"); });
        QVERIFY2(message.startsWith("my.json: "), qPrintable(message));
        QVERIFY2(message.contains(field), qPrintable(message));
    }

    void fileErrors() {
        const QTemporaryDir dir;
        const std::string missing = dir.filePath("missing.json").toStdString();
        QString message = errorOf([&] { readTransferFunction(missing); });
        QVERIFY2(message.startsWith(QString::fromStdString(missing)), qPrintable(message));
        message = errorOf([&] {
            writeTransferFunction(sample(), dir.filePath("no/such/dir.json").toStdString());
        });
        QVERIFY2(message.contains("dir.json"), qPrintable(message));
    }

    void presets() {
        const std::vector<std::string> names = presetNames();
        for (const char* expected :
             {"ct-bone", "ct-soft-tissue", "ct-lung", "ct-angio", "ct-mip", "mr-default"}) {
            QVERIFY2(std::find(names.begin(), names.end(), expected) != names.end(), expected);
        }
        for (const std::string& name : names) {
            const TransferFunction tf = loadPreset(name);
            tf.validate();
            QCOMPARE(QString::fromStdString(tf.name), QString::fromStdString(name));
            QCOMPARE(QString::fromStdString(tf.modality), name.starts_with("mr") ? "MR" : "CT");
        }
        // Slicer's CT-Bone numbers, copied.
        const TransferFunction bone = loadPreset("ct-bone");
        QCOMPARE(bone.opacityAt(641.385), 0.715686);
        QCOMPARE(bone.maxOpacity(-3024.0, -16.4458), 0.0);
    }

    void unknownPreset() {
        for (const char* name : {"no-such-preset", "../presets/ct-bone", ""}) {
            const QString message = errorOf([&] { loadPreset(name); });
            QVERIFY2(message.contains(QString("'%1'").arg(name)), qPrintable(message));
            QVERIFY2(message.contains("ct-bone") && message.contains("mr-default"),
                     qPrintable(message));
        }
    }

    void presetDirectoryFromEnvironment() {
        const QTemporaryDir dir;
        {
            std::ofstream(dir.filePath("ct-bone.json").toStdString()) << kValid.toStdString();
            std::ofstream(dir.filePath("broken.json").toStdString())
                << R"({"opacity": [[0, 2]], "colour": [[0, 0, 0, 0]]})";
        }
        ::setenv("LUCENT_PRESET_DIR", dir.path().toUtf8().constData(), 1);
        const auto directories = presetDirectories();
        const TransferFunction overridden = loadPreset("ct-bone");
        const QString message = errorOf([] { loadPreset("broken"); });
        const std::vector<std::string> names = presetNames();
        ::unsetenv("LUCENT_PRESET_DIR");
        QVERIFY(!directories.empty());
        QCOMPARE(QString::fromStdString(directories.front().string()), dir.path());
        QVERIFY(overridden.opacity.size() == 2); // the file in $LUCENT_PRESET_DIR wins
        QVERIFY2(message.contains("broken.json: field 'opacity[0]'"), qPrintable(message));
        QVERIFY(std::find(names.begin(), names.end(), "broken") != names.end());
        QVERIFY(std::find(names.begin(), names.end(), "ct-lung") != names.end());
    }

    void bakedTable() {
        const TransferFunction tf = loadPreset("ct-angio");
        const TfTable table = bakeTable(tf, -1024.0, 3071.0, 4096);
        QCOMPARE(table.rgba.size(), std::size_t(4096));
        for (int n = 0; n < 4096; n += 7) {
            const double value = -1024.0 + n * 4095.0 / 4095.0;
            const glm::dvec4 expected(tf.colourAt(value), tf.opacityAt(value));
            QVERIFY(maxDifference(glm::dvec4(table.rgba[std::size_t(n)]), expected) < 1e-7);
            QVERIFY(maxDifference(glm::dvec4(table.lookup(value)), expected) < 1e-6);
        }
        // Linear between entries, clamped beyond the ends.
        const glm::vec4 mid = table.lookup(100.5);
        QVERIFY(maxDifference(glm::dvec4(mid),
                              glm::dvec4(0.5f * (table.rgba[1124] + table.rgba[1125]))) < 1e-6);
        QVERIFY(table.lookup(-5000.0) == table.rgba.front());
        QVERIFY(table.lookup(1e9) == table.rgba.back());
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, bakeTable(tf, 0.0, 1.0, 1));
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, bakeTable(tf, 1.0, 1.0, 16));
    }

    void preintegrationExactOnDiagonal() {
        for (const char* name : {"ct-bone", "ct-soft-tissue", "ct-lung", "mr-default"}) {
            const TransferFunction tf = loadPreset(name);
            const PreintegrationTable table =
                buildPreintegrationTable(tf, -1000.0, 1000.0, 33, 1.7);
            for (double r : {0.01, 0.25, 0.5, 1.0, 1.7, 4.0}) {
                for (double s = -1000.0; s <= 1000.0; s += 62.5) {
                    const glm::dvec4 got = preintegrateSegment(tf, s, s, r);
                    QVERIFY2(maxDifference(got, closedForm(tf, s, r)) < 1e-12, name);
                }
            }
            for (int n = 0; n < 33; ++n) {
                const double s = -1000.0 + n * 62.5;
                const glm::vec4 entry = table.rgba[std::size_t(n + 33 * n)];
                QVERIFY(maxDifference(glm::dvec4(entry), closedForm(tf, s, 1.7)) < 1e-7);
                QVERIFY(table.lookup(s, s) == entry);
            }
        }
    }

    void preintegrationMatchesBruteForce_data() {
        QTest::addColumn<QString>("preset");
        QTest::addColumn<double>("front");
        QTest::addColumn<double>("back");
        QTest::addColumn<double>("stepRatio");
        QTest::newRow("bone ramp") << "ct-bone" << -100.0 << 900.0 << 1.0;
        QTest::newRow("bone ramp backwards") << "ct-bone" << 900.0 << -100.0 << 1.0;
        QTest::newRow("bone thick") << "ct-bone" << 0.0 << 3000.0 << 8.0;
        QTest::newRow("angio steep") << "ct-angio" << 100.0 << 300.0 << 1.0;
        QTest::newRow("angio thin") << "ct-angio" << 129.0 << 131.0 << 0.3;
        QTest::newRow("lung slab") << "ct-lung" << -800.0 << -300.0 << 2.0;
        QTest::newRow("soft tissue into opaque") << "ct-soft-tissue" << -200.0 << 0.0 << 1.0;
        QTest::newRow("soft tissue from opaque") << "ct-soft-tissue" << 0.0 << -200.0 << 0.5;
        QTest::newRow("mip ramp") << "ct-mip" << -1000.0 << 1000.0 << 0.2;
        QTest::newRow("mr") << "mr-default" << 0.0 << 400.0 << 1.5;
        QTest::newRow("mr tiny step") << "mr-default" << 30.0 << 150.0 << 0.01;
    }

    // The documented accuracy: 1e-4 absolute in rgb and alpha.
    void preintegrationMatchesBruteForce() {
        QFETCH(QString, preset);
        QFETCH(double, front);
        QFETCH(double, back);
        QFETCH(double, stepRatio);
        const TransferFunction tf = loadPreset(preset.toStdString());
        const glm::dvec4 got = preintegrateSegment(tf, front, back, stepRatio);
        const glm::dvec4 reference = bruteForce(tf, front, back, stepRatio);
        const double error = maxDifference(got, reference);
        QVERIFY2(error < 1e-4, qPrintable(QString("error %1").arg(error)));
        QVERIFY(got.w >= 0.0 && got.w <= 1.0);
        QVERIFY(got.x <= got.w + 1e-12 && got.y <= got.w + 1e-12 && got.z <= got.w + 1e-12);
    }

    void preintegrationLimits() {
        const TransferFunction tf = loadPreset("ct-bone");
        double previous = 0.0;
        for (double r : {1e-9, 1e-6, 1e-3, 0.1, 0.5, 1.0, 2.0, 8.0, 64.0}) {
            const double alpha = preintegrateSegment(tf, 100.0, 2000.0, r).w;
            QVERIFY(alpha > previous && alpha <= 1.0); // more path, more opacity
            previous = alpha;
        }
        QVERIFY(preintegrateSegment(tf, 100.0, 2000.0, 1e-9).w < 1e-8); // small step -> 0
        QVERIFY(preintegrateSegment(tf, 100.0, 2000.0, 1e3).w > 1.0 - 1e-12);
        QVERIFY(preintegrateSegment(tf, -2000.0, -100.0, 1.0) == glm::dvec4(0.0)); // empty
        // Continuity towards the diagonal.
        const glm::dvec4 diagonal = preintegrateSegment(tf, 500.0, 500.0, 1.0);
        QVERIFY(maxDifference(preintegrateSegment(tf, 500.0, 500.001, 1.0), diagonal) < 1e-6);
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, preintegrateSegment(tf, 0.0, 1.0, 0.0));
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument,
                                 buildPreintegrationTable(tf, 0.0, 1.0, 16, -1.0));
    }

    void preintegrationTable() {
        const TransferFunction tf = loadPreset("ct-angio");
        const PreintegrationTable table = buildPreintegrationTable(tf, -200.0, 800.0, 128, 0.7);
        QCOMPARE(table.size, 128);
        QCOMPARE(table.rgba.size(), std::size_t(128 * 128));
        const auto value = [](int n) { return -200.0 + n * 1000.0 / 127.0; };
        for (const auto& [i, j] : std::initializer_list<std::pair<int, int>>{
                 {3, 90}, {90, 3}, {40, 41}, {127, 0}, {0, 127}}) {
            const glm::vec4 entry = table.rgba[std::size_t(i + 128 * j)];
            const glm::dvec4 expected = preintegrateSegment(tf, value(i), value(j), 0.7);
            QVERIFY(maxDifference(glm::dvec4(entry), expected) < 1e-6);
            QVERIFY(maxDifference(glm::dvec4(table.lookup(value(i), value(j))), expected) < 1e-5);
        }
        // Bilinear between entries, clamped outside.
        const glm::vec4 a = table.rgba[10 + 128 * 20], b = table.rgba[11 + 128 * 20];
        QVERIFY(maxDifference(glm::dvec4(table.lookup(0.5 * (value(10) + value(11)), value(20))),
                              glm::dvec4(0.5f * (a + b))) < 1e-6);
        QVERIFY(table.lookup(-1e6, 1e6) == table.rgba[128 * 127]);
    }
};

QTEST_APPLESS_MAIN(TestTransferFunction)
#include "test_transfer_function.moc"
