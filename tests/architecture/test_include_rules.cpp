// The dependency rules of docs/DESIGN.md on the real tree, and proof on small trees that each
// rule reports what it should and nothing else.
#include <QTest>

#include <QDir>
#include <QFile>
#include <QFileInfo>
#include <QTemporaryDir>

#include "tests/architecture/IncludeRules.h"

using namespace lucent::arch;

namespace {

QString listed(const QList<Violation>& violations) {
    QStringList lines;
    for (const Violation& v : violations) {
        lines << "  " + v.toString();
    }
    return lines.join('\n');
}

// "rule:line" for each violation, to compare against what a row expects.
QStringList ruleLines(const QList<Violation>& violations) {
    QStringList out;
    for (const Violation& v : violations) {
        out << QStringLiteral("%1:%2").arg(ruleName(v.rule)).arg(v.line);
    }
    out.sort();
    return out;
}

bool writeFile(const QString& root, const QString& relPath, const QString& text) {
    const QString path = root + '/' + relPath;
    if (!QDir().mkpath(QFileInfo(path).path())) {
        return false;
    }
    QFile file(path);
    return file.open(QIODevice::WriteOnly | QIODevice::Truncate) &&
           file.write(text.toUtf8()) == text.toUtf8().size();
}

} // namespace

class TestIncludeRules : public QObject {
    Q_OBJECT

    Config config_;
    Report realTree_;

private slots:
    void initTestCase() {
        config_.widgetHeaders = widgetHeadersFromQt();
        config_.glFunctions = glFunctionsFromEpoxy(QStringLiteral(LUCENT_EPOXY_GL_GENERATED));
        QVERIFY2(!config_.glFunctions.isEmpty(),
                 "no GL entry points read from " LUCENT_EPOXY_GL_GENERATED
                 " (libepoxy-dev): without them every gl[A-Z]...( call would count");
        QVERIFY(config_.glFunctions.contains("glClear"));
        QVERIFY(config_.widgetHeaders.contains("QWidget"));
        QVERIFY(config_.widgetHeaders.contains("QPushButton"));
        QVERIFY(config_.widgetHeaders.contains("QOpenGLWidget"));
        QVERIFY(!config_.widgetHeaders.contains("QAction")); // QtGui in Qt 6
        qInfo("%lld widget headers, %lld GL entry points", qlonglong(config_.widgetHeaders.size()),
              qlonglong(config_.glFunctions.size()));
        realTree_ = checkTree(QStringLiteral(LUCENT_SOURCE_DIR), config_);
    }

    // The real tree: every violation is listed, and any the allow list does not hold fails.
    void realTreeKeepsTheRules() {
        QVERIFY2(realTree_.filesChecked > 100, qPrintable(QStringLiteral("only %1 files under %2")
                                                              .arg(realTree_.filesChecked)
                                                              .arg(LUCENT_SOURCE_DIR)));
        QVERIFY2(realTree_.unreadable.isEmpty(), qPrintable(realTree_.unreadable.join(", ")));
        const QList<Violation>& broken = realTree_.violations;
        // One message per violation: QTest cuts a single long message short.
        for (const Violation& v : broken) {
            qWarning().noquote() << v.toString();
        }
        QVERIFY2(broken.isEmpty(),
                 qPrintable(QStringLiteral("%1 include rule violation(s) in %2 files, listed above")
                                .arg(broken.size())
                                .arg(realTree_.filesChecked)));
    }

    void reportsViolation_data() {
        QTest::addColumn<QString>("path");
        QTest::addColumn<QString>("text");
        QTest::addColumn<QStringList>("expected"); // "rule:line"

        QTest::newRow("core includes render")
            << "core/volume/Bad.cpp"
            << "#include <vector>\n#include \"render/GpuRayCaster.h\"\n"
            << QStringList{"layers:2"};
        QTest::newRow("core includes render, relative") << "core/volume/Bad.cpp"
                                                        << "#include \"../../render/Support.h\"\n"
                                                        << QStringList{"layers:1"};
        QTest::newRow("core includes protocol, spaced")
            << "core/Bad.h"
            << "#pragma once\n  #  include   \"protocol/ProtocolMessages.h\"\n"
            << QStringList{"layers:2"};
        QTest::newRow("protocol includes server")
            << "protocol/Bad.h"
            << "#pragma once\n\n#include \"server/RenderServer.h\"\n"
            << QStringList{"layers:3"};
        QTest::newRow("render includes ui") << "render/Bad.cpp"
                                            << "#include \"ui/volume/VolumeView.h\"\n"
                                            << QStringList{"layers:1"};
        QTest::newRow("server includes ui") << "server/Bad.cpp"
                                            << "#include \"ui/app/MainWindow.h\"\n"
                                            << QStringList{"layers:1"};
        QTest::newRow("ui includes server") << "ui/volume/Bad.cpp"
                                            << "#include \"server/RenderServer.h\"\n"
                                            << QStringList{"layers:1"};
        QTest::newRow("render includes QWidget") << "render/Bad.cpp"
                                                 << "#include <QImage>\n#include <QWidget>\n"
                                                 << QStringList{"widgets:2"};
        QTest::newRow("server includes QtWidgets/QLabel") << "server/Bad.cpp"
                                                          << "#include <QtWidgets/QLabel>\n"
                                                          << QStringList{"widgets:1"};
        QTest::newRow("lucent-cli includes QDialog") << "app/lucent-cli/Bad.cpp"
                                                     << "#include <QDialog>\n"
                                                     << QStringList{"widgets:1"};
        QTest::newRow("render includes QOpenGLWidget") << "render/Bad.cpp"
                                                       << "#include <QOpenGLWidget>\n"
                                                       << QStringList{"gl:1", "widgets:1"};
        QTest::newRow("ui/mpr includes QOpenGLContext") << "ui/mpr/Bad.cpp"
                                                        << "#include <QOpenGLContext>\n"
                                                        << QStringList{"gl:1"};
        QTest::newRow("lucent-cli includes EGL") << "app/lucent-cli/Bad.cpp"
                                                 << "#include <EGL/egl.h>\n"
                                                 << QStringList{"gl:1"};
        QTest::newRow("server includes epoxy") << "server/Bad.cpp"
                                               << "#include <epoxy/gl.h>\n"
                                               << QStringList{"gl:1"};
        QTest::newRow("core header includes gdcm") << "core/dicom/Bad.h"
                                                   << "#pragma once\n#include <gdcmReader.h>\n"
                                                   << QStringList{"third-party:2"};
        QTest::newRow("core header includes dcmtk")
            << "core/pacs/Bad.h"
            << "#pragma once\n#include <dcmtk/dcmnet/scu.h>\n"
            << QStringList{"third-party:2"};
        QTest::newRow("render header includes epoxy") << "render/Bad.h"
                                                      << "#pragma once\n#include <epoxy/gl.h>\n"
                                                      << QStringList{"third-party:2"};
        QTest::newRow("render includes a private header of core/dicom")
            << "render/Bad.cpp"
            << "// tags\n#include \"core/dicom/Tags_p.h\"\n"
            << QStringList{"layers:2"};
        QTest::newRow("render header includes mpi") << "render/distributed/Bad.h"
                                                    << "#pragma once\n#include <mpi.h>\n"
                                                    << QStringList{"third-party:2"};
        QTest::newRow("core header includes FFmpeg")
            << "core/movie/Bad.h"
            << "#pragma once\nextern \"C\" {\n#include <libavcodec/avcodec.h>\n}\n"
            << QStringList{"third-party:3"};
        QTest::newRow("render header includes IceT") << "render/distributed/Bad.h"
                                                     << "#pragma once\n#include <IceT.h>\n"
                                                     << QStringList{"third-party:2"};
        QTest::newRow("ui calls glClear")
            << "ui/mpr/Bad.cpp"
            << "void clear(QOpenGLFunctions* gl) {\n    gl->glClear(GL_COLOR_BUFFER_BIT);\n}\n"
            << QStringList{"gl:2"};
        QTest::newRow("lucent calls glViewport") << "app/lucent/Bad.cpp"
                                                 << "void f() {\n    glViewport(0, 0, 1, 1);\n}\n"
                                                 << QStringList{"gl:2"};
    }

    // One deliberate violation in an otherwise clean tree: reported, with its rule and line.
    void reportsViolation() {
        QFETCH(QString, path);
        QFETCH(QString, text);
        QFETCH(QStringList, expected);
        QTemporaryDir dir;
        QVERIFY(dir.isValid());
        QVERIFY(writeFile(dir.path(), "render/Support.h", "#pragma once\n"));
        QVERIFY(writeFile(dir.path(), path, text));
        const Report report = checkTree(dir.path(), config_);
        QCOMPARE(report.filesChecked, 2);
        for (const Violation& v : report.violations) {
            QCOMPARE(v.file, path);
        }
        QCOMPARE(ruleLines(report.violations), expected);
    }

    // Everything each folder may do, and what looks like a violation but is not.
    void cleanTreeReportsNothing() {
        QTemporaryDir dir;
        QVERIFY(dir.isValid());
        const QString root = dir.path();
        const QList<std::pair<QString, QString>> files = {
            {"core/scene/Camera.h", "#pragma once\n#include <glm/glm.hpp>\n"},
            {"core/volume/Volume.h", "#pragma once\n#include <vector>\n"
                                     "#include \"core/scene/Camera.h\"\n"},
            {"core/dicom/Reader.cpp",
             "#include <gdcmReader.h>\n#include <dcmtk/dcmdata/dcfilefo.h>\n"
             "#include \"core/volume/Volume.h\"\n#include \"Reader.h\"\n"
             "// gl->glClear(GL_COLOR_BUFFER_BIT) would be wrong here\n"
             "/*\n#include \"render/GpuRayCaster.h\"\n#include <QWidget>\n*/\n"
             "const char* s = \"glClear(\";\n"
             "const char* r = R\"x(glClear( \" #include <QWidget>)x\";\n"
             "const char c = '\"';\nint n = 1'000'000; // glClear(\n"},
            {"core/dicom/Reader.h", "#pragma once\n#include <string>\n"},
            // A private header ("_p.h") may show the library; its folder includes it.
            {"core/dicom/Tags_p.h", "#pragma once\n#include <gdcmDataSet.h>\n"},
            {"core/dicom/Tags.cpp", "#include \"core/dicom/Tags_p.h\"\n#include \"Tags_p.h\"\n"},
            {"protocol/Messages.h", "#pragma once\n#include \"core/scene/Camera.h\"\n"},
            {"protocol/Messages.cpp",
             "#include \"protocol/Messages.h\"\n#include \"core/volume/Volume.h\"\n"},
            {"render/Caster.h", "#pragma once\n#include <QAction>\n#include <QImage>\n"
                                "#include \"protocol/Messages.h\"\n"},
            {"render/Caster.cpp", "#include <epoxy/gl.h>\n#include <EGL/egl.h>\n"
                                  "#include <QOpenGLContext>\n#include \"render/Caster.h\"\n"
                                  "void f() { glClear(GL_COLOR_BUFFER_BIT); }\n"},
            {"server/Server.cpp", "#include <QWebSocketServer>\n#include \"render/Caster.h\"\n"
                                  "#include \"protocol/Messages.h\"\n#include \"core/scene/"
                                  "Camera.h\"\n"},
            {"ui/volume/View.h", "#pragma once\n#include <QOpenGLWidget>\n#include <QWidget>\n"},
            {"ui/volume/View.cpp", "#include <QOpenGLFunctions>\n#include "
                                   "<QOpenGLContext>\n#include \"render/Caster.h\"\n"
                                   "QString glUnavailableReason() { return {}; }\n"
                                   "void g() { auto r = glUnavailableReason(); }\n"},
            {"ui/app/Window.cpp", "#include <QtWidgets/QMainWindow>\n#include <QOpenGLWidget>\n"
                                  "#include \"ui/volume/View.h\"\n"},
            {"app/lucent/main.cpp", "#include <QApplication>\n#include \"ui/volume/View.h\"\n"
                                    "#include \"server/Server.h\"\n"},
            {"app/lucent-cli/main.cpp", "#include \"CliCommand.h\"\n#include \"render/Caster.h\"\n"
                                        "#include \"ui/volume/View.h\"\n"},
            {"app/lucent-cli/CliCommand.h", "#pragma once\n#include <QString>\n"},
        };
        for (const auto& [path, text] : files) {
            QVERIFY(writeFile(root, path, text));
        }
        // Outside the source folders nothing is checked.
        QVERIFY(writeFile(root, "tests/core/test_x.cpp",
                          "#include <QWidget>\n#include \"ui/app/Window.h\"\nvoid f() { "
                          "glClear(0); }\n"));
        const Report report = checkTree(root, config_);
        QCOMPARE(report.filesChecked, int(files.size()));
        QVERIFY2(report.violations.isEmpty(), qPrintable(listed(report.violations)));
    }

    void blanksCommentsAndLiterals() {
        const QString text = "a /* b\nc */ d // e\n\"f\" 'g' R\"(h\ni)\" 1'0";
        QCOMPARE(blankComments(text, false),
                 QString("a     \n     d     \n\"f\" 'g' R\"(h\ni)\" 1'0"));
        QCOMPARE(blankComments(text, true),
                 QString("a     \n     d     \n\" \" ' ' R\"  \n  \" 1'0"));
    }

    void violationNamesFileLineIncludeAndRule() {
        const QList<Violation> v =
            checkFile(QString(), "core/Bad.h", "#pragma once\n#include \"render/X.h\"\n", config_);
        QCOMPARE(v.size(), 1);
        QCOMPARE(v[0].toString(), QString("core/Bad.h:2: #include \"render/X.h\" -- layers: core/ "
                                          "may include only core/"));
    }
};

QTEST_GUILESS_MAIN(TestIncludeRules)
#include "test_include_rules.moc"
