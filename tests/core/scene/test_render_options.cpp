// The render options table: every row reads and writes its own field, refuses
// what is out of range naming the option, and docs/options.md is its output.
#include <QTest>

#include <fstream>
#include <set>
#include <sstream>
#include <stdexcept>

#include "core/scene/DefaultPreset.h"
#include "core/scene/RenderOptions.h"

using namespace lucent;

namespace {

// Some valid text for an option other than its default.
std::string otherValue(const RenderOption& o) {
    switch (o.kind) {
    case OptionKind::Number:
    case OptionKind::Integer:
        if (o.max >= 7.0 && o.min <= 7.0) {
            return "7";
        }
        return renderOptionDefault(o) == "0.5" ? "0.25" : "0.5";
    case OptionKind::Choice:
        return std::string(o.choices.back());
    case OptionKind::Switch:
        return renderOptionDefault(o) == "true" ? "false" : "true";
    case OptionKind::Size:
        return "300x200";
    case OptionKind::Box:
        return "1,2,3,40,50.5,60";
    case OptionKind::Window:
        return "300,600.5";
    }
    return {};
}

bool refuses(const RenderOption& o, const std::string& text, const std::string& word) {
    RenderDescription d;
    try {
        applyRenderOption(d, o, text);
    } catch (const std::invalid_argument& e) {
        return std::string(e.what()).find(word) != std::string::npos;
    }
    return false;
}

} // namespace

class TestRenderOptions : public QObject {
    Q_OBJECT

private slots:
    void namesAreUnique() {
        std::set<std::string_view> names, flags;
        std::set<std::string> wire;
        for (const RenderOption& o : renderOptions()) {
            QVERIFY2(names.insert(o.name).second, o.name.data());
            if (!o.cliFlag.empty()) {
                QVERIFY2(flags.insert(o.cliFlag).second, o.cliFlag.data());
            }
            if (!o.wireKey.empty()) {
                QVERIFY(!o.wireMessage.empty());
                QVERIFY2(
                    wire.insert(std::string(o.wireMessage) + "." + std::string(o.wireKey)).second,
                    o.wireKey.data());
            }
            QVERIFY(!o.help.empty() && o.read && o.write);
            QCOMPARE(findRenderOption(o.name), &o);
        }
    }

    // Each row reaches its own field and no other.
    void eachRowWritesItsField() {
        for (const RenderOption& o : renderOptions()) {
            RenderDescription d;
            const std::string value = otherValue(o);
            QVERIFY2(value != renderOptionDefault(o), o.name.data());
            applyRenderOption(d, o, value);
            QCOMPARE(renderOptionValue(d, o), value);
            for (const RenderOption& other : renderOptions()) {
                if (&other != &o && other.name != o.name) {
                    QVERIFY2(
                        renderOptionValue(d, other) == renderOptionDefault(other),
                        qPrintable(
                            QString("%1 changed %2").arg(o.name.data()).arg(other.name.data())));
                }
            }
        }
    }

    void refusalsNameTheOption() {
        QVERIFY(refuses(*findRenderOption("step"), "0", "step"));
        QVERIFY(refuses(*findRenderOption("step"), "fast", "not a number"));
        QVERIFY(refuses(*findRenderOption("step"), "nan", "step"));
        QVERIFY(refuses(*findRenderOption("zoom"), "-1", "zoom"));
        QVERIFY(refuses(*findRenderOption("brick"), "2.5", "whole number"));
        QVERIFY(refuses(*findRenderOption("early-termination"), "1.5", "early termination"));
        QVERIFY(refuses(*findRenderOption("interp"), "bicubic", "nearest, linear, cubic"));
        QVERIFY(refuses(*findRenderOption("shading"), "yes", "true or false"));
        QVERIFY(refuses(*findRenderOption("size"), "512", "WIDTHxHEIGHT"));
        QVERIFY(refuses(*findRenderOption("size"), "0x10", "out of range"));
        QVERIFY(refuses(*findRenderOption("size"), "20000x10", "out of range"));
        for (const char* window : {"300", "300,0", "300,-5", "a,600", "300,inf", ""}) {
            QVERIFY2(refuses(*findRenderOption("overlay-window"), window, "is not C,W"), window);
        }
        QVERIFY(refuses(*findRenderOption("overlay-opacity"), "1.5", "overlay opacity"));
        QVERIFY(refuses(*findRenderOption("overlay-map"), "jet", "grey, hot-iron, rainbow, pet"));
        RenderDescription d;
        applyRenderOption(d, *findRenderOption("overlay-window"), "auto");
        QCOMPARE(d.overlay.style.width, 0.0);
    }

    // validate() checks the table's ranges for descriptions made in code too.
    void validateUsesTheTable() {
        RenderDescription d;
        d.transferFunction.opacity = {{0.0, 0.0}, {1.0, 1.0}};
        d.transferFunction.colour = {{0.0, glm::dvec3(1.0)}};
        d.validate();
        d.sampling.brickSize = 5000;
        try {
            d.validate();
            QFAIL("a brick of 5000 was accepted");
        } catch (const std::invalid_argument& e) {
            QVERIFY2(std::string(e.what()).find("brick size") != std::string::npos, e.what());
        }
        d.sampling.brickSize = 64;
        d.camera.distance = -1.0;
        try {
            d.validate();
            QFAIL("a negative distance was accepted");
        } catch (const std::invalid_argument& e) {
            QVERIFY2(std::string(e.what()).find("camera distance") != std::string::npos, e.what());
        }
    }

    void imageSizes() {
        QCOMPARE(parseImageSize("640x480"), std::make_pair(640, 480));
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, parseImageSize("640x"));
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, parseImageSize("x480"));
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, parseImageSize("64 0x480"));
    }

    void defaultPresets() {
        QCOMPARE(defaultPresetName("CT", RenderMode::Dvr), std::string("ct-bone"));
        QCOMPARE(defaultPresetName("CT", RenderMode::Mip), std::string("ct-mip"));
        QCOMPARE(defaultPresetName("MR", RenderMode::Dvr), std::string("mr-default"));
        QCOMPARE(defaultPresetName("", RenderMode::Dvr), std::string("mr-default"));
    }

    // The docs print the table as it is: regenerate with `lucent-cli options --markdown`.
    void docsListEveryOption() {
        std::ifstream in(LUCENT_SOURCE_DIR "/docs/options.md");
        QVERIFY2(in, "docs/options.md is missing");
        std::stringstream text;
        text << in.rdbuf();
        const std::string md = renderOptionsMarkdown();
        QVERIFY2(text.str().find(md) != std::string::npos,
                 "docs/options.md does not hold the options table: run "
                 "build/bin/lucent-cli options --markdown and paste it");
    }
};

QTEST_APPLESS_MAIN(TestRenderOptions)
#include "test_render_options.moc"
