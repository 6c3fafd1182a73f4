#include "tests/architecture/IncludeRules.h"

#include <QDir>
#include <QDirIterator>
#include <QFile>
#include <QFileInfo>
#include <QHash>
#include <QLibraryInfo>
#include <QRegularExpression>

#include <algorithm>

namespace lucent::arch {

namespace {

// What each source folder may include besides itself (rule 1). app/ may include anything.
const QHash<QString, QStringList>& allowedLayers() {
    static const QHash<QString, QStringList> allowed = {
        {"core", {"core"}},
        {"protocol", {"protocol", "core"}},
        {"render", {"render", "protocol", "core"}},
        {"server", {"server", "render", "protocol", "core"}},
        {"ui", {"ui", "render", "protocol", "core"}},
        {"app", kSourceFolders},
    };
    return allowed;
}

// Third-party libraries whose headers stay in .cpp files (rule 4): GDCM, DCMTK, libjpeg-turbo,
// CharLS, OpenJPEG, EGL and the GL headers (epoxy, Khronos), MPI, IceT, FFmpeg, libarchive,
// libplist and ITK (core/registration).
bool isThirdPartyHeader(const QString& include) {
    static const QStringList prefixes = {
        "gdcm",  "dcmtk/", "EGL/",      "epoxy/",          "GL/",         "GLES2/", "GLES3/",
        "KHR/",  "charls", "openjpeg",  "jpeglib.h",       "turbojpeg.h", "mpi.h",  "IceT",
        "libav", "libsw",  "archive.h", "archive_entry.h", "plist/",      "itk"};
    return std::any_of(prefixes.begin(), prefixes.end(),
                       [&](const QString& p) { return include.startsWith(p); });
}

// GL headers other than Qt's (rule 2).
bool isNativeGlHeader(const QString& include) {
    static const QStringList prefixes = {"epoxy/", "GL/", "EGL/", "GLES2/", "GLES3/", "KHR/"};
    return std::any_of(prefixes.begin(), prefixes.end(),
                       [&](const QString& p) { return include.startsWith(p); });
}

// <QtGui/QOpenGLContext> -> module "QtGui", name "QOpenGLContext"; <QWidget> -> "", "QWidget".
struct QtHeader {
    QString module;
    QString name;
};

QtHeader splitQtHeader(const QString& include) {
    const qsizetype slash = include.indexOf('/');
    if (slash < 0) {
        return {QString(), include};
    }
    return {include.left(slash), include.mid(slash + 1)};
}

bool isQOpenGLWidgetHeader(const QtHeader& h) {
    return h.module == "QtOpenGLWidgets" ||
           (h.module.isEmpty() && (h.name == "QtOpenGLWidgets" || h.name == "QOpenGLWidget" ||
                                   h.name == "qopenglwidget.h"));
}

// Qt's GL classes (QOpenGLContext, QOpenGLFunctions, ...) and the QtOpenGL module.
bool isQtGlHeader(const QtHeader& h) {
    if (h.module == "QtOpenGL" || (h.module.isEmpty() && h.name == "QtOpenGL")) {
        return true;
    }
    return (h.module.isEmpty() || h.module == "QtGui") &&
           (h.name.startsWith("QOpenGL") || h.name.startsWith("qopengl"));
}

bool isWidgetHeader(const QtHeader& h, const Config& config) {
    if (h.module == "QtWidgets" || h.module == "QtOpenGLWidgets") {
        return true;
    }
    return h.module.isEmpty() && config.widgetHeaders.contains(h.name);
}

bool isHeaderFile(const QString& path) {
    return path.endsWith(".h") || path.endsWith(".hpp");
}

bool under(const QString& path, const QString& folder) {
    return path.startsWith(folder + '/');
}

QString firstComponent(const QString& path) {
    const qsizetype slash = path.indexOf('/');
    return slash < 0 ? QString() : path.left(slash);
}

// The path, relative to the root, of the header an include names ("render/GpuRayCaster.h" for
// "render/GpuRayCaster.h", or for "../render/GpuRayCaster.h" written in core/x/).
QString projectHeaderPath(const QString& root, const QString& relPath, const QString& include,
                          bool quoted) {
    QString target = QDir::cleanPath(include);
    if (quoted) {
        const QString dir = QFileInfo(relPath).path();
        const QString besideFile = QDir::cleanPath(dir + '/' + include);
        if (!besideFile.startsWith("../") && QFileInfo::exists(root + '/' + besideFile)) {
            target = besideFile;
        }
    }
    return target;
}

// The project folder an include points into ("render"), or "" for anything else.
QString projectFolderOf(const QString& root, const QString& relPath, const QString& include,
                        bool quoted) {
    const QString folder = firstComponent(projectHeaderPath(root, relPath, include, quoted));
    return kSourceFolders.contains(folder) ? folder : QString();
}

QString folderList(const QStringList& folders) {
    QStringList withSlash;
    for (const QString& f : folders) {
        withSlash << f + '/';
    }
    return withSlash.join(", ");
}

Violation make(const QString& file, int line, const QString& subject, Rule rule,
               const QString& reason) {
    return Violation{file, line, subject, rule, reason};
}

void checkInclude(const QString& root, const QString& relPath, int line, const QString& include,
                  bool quoted, const Config& config, QList<Violation>& out) {
    const QString subject =
        QStringLiteral("#include ") + (quoted ? '"' + include + '"' : '<' + include + '>');
    const QString layer = firstComponent(relPath);

    // (1) Layers.
    const QString target = projectFolderOf(root, relPath, include, quoted);
    if (!target.isEmpty()) {
        const QStringList& allowed = allowedLayers().value(layer);
        if (!allowed.contains(target)) {
            out << make(
                relPath, line, subject, Rule::Layers,
                QStringLiteral("layers: %1/ may include only %2").arg(layer, folderList(allowed)));
        }
        // A private header (Qt's "_p.h") belongs to its folder.
        const QString resolved = projectHeaderPath(root, relPath, include, quoted);
        if (resolved.endsWith(QStringLiteral("_p.h")) &&
            QFileInfo(resolved).path() != QFileInfo(relPath).path()) {
            out << make(relPath, line, subject, Rule::Layers,
                        QStringLiteral("layers: %1 is private to %2/")
                            .arg(resolved, QFileInfo(resolved).path()));
        }
        return; // a project header is none of the kinds below
    }

    const QtHeader qt = splitQtHeader(include);

    // (2) GL headers: render/ and ui/volume/; QOpenGLWidget, a widget, in ui/ only.
    if (isQOpenGLWidgetHeader(qt)) {
        if (layer != "ui") {
            out << make(relPath, line, subject, Rule::Gl,
                        QStringLiteral("gl: QOpenGLWidget only in ui/"));
        }
    } else if (isNativeGlHeader(include) || isQtGlHeader(qt)) {
        if (layer != "render" && !under(relPath, "ui/volume")) {
            out << make(relPath, line, subject, Rule::Gl,
                        QStringLiteral("gl: GL headers only in render/ and ui/volume/"));
        }
    }

    // (3) Widgets: ui/ and app/lucent/ only.
    if (isWidgetHeader(qt, config) && layer != "ui" && !under(relPath, "app/lucent")) {
        out << make(relPath, line, subject, Rule::Widgets,
                    QStringLiteral("widgets: Qt Widgets headers only in ui/ and app/lucent/"));
    }

    // (4) Third-party headers: .cpp files only, in the libraries' folders.
    if (isHeaderFile(relPath) && !relPath.endsWith(QStringLiteral("_p.h")) && layer != "app" &&
        isThirdPartyHeader(include)) {
        out << make(relPath, line, subject, Rule::ThirdParty,
                    QStringLiteral("third-party: library headers only in .cpp files and private "
                                   "headers (_p.h), not in a public header of %1/")
                        .arg(layer));
    }
}

bool isIdentifierChar(QChar c) {
    return c.isLetterOrNumber() || c == '_';
}

} // namespace

QString ruleName(Rule rule) {
    switch (rule) {
    case Rule::Layers:
        return QStringLiteral("layers");
    case Rule::Gl:
        return QStringLiteral("gl");
    case Rule::Widgets:
        return QStringLiteral("widgets");
    case Rule::ThirdParty:
        return QStringLiteral("third-party");
    }
    return QString();
}

QString Violation::toString() const {
    return QStringLiteral("%1:%2: %3 -- %4").arg(file).arg(line).arg(subject, reason);
}

QSet<QString> widgetHeadersFromQt() {
    const QDir headers(QLibraryInfo::path(QLibraryInfo::HeadersPath));
    QSet<QString> widgets;
    for (const char* module : {"QtWidgets", "QtOpenGLWidgets"}) {
        for (const QString& name : QDir(headers.filePath(module)).entryList(QDir::Files)) {
            widgets.insert(name);
        }
    }
    // Qt 6 keeps forwarding headers in QtWidgets for classes that moved to QtGui (qaction.h):
    // those are not widgets.
    for (const char* module : {"QtGui", "QtCore"}) {
        for (const QString& name : QDir(headers.filePath(module)).entryList(QDir::Files)) {
            widgets.remove(name);
        }
    }
    if (widgets.isEmpty()) {
        widgets = {"QtWidgets",      "QApplication", "QWidget",       "QMainWindow", "QDialog",
                   "QPushButton",    "QLabel",       "QLineEdit",     "QComboBox",   "QCheckBox",
                   "QSpinBox",       "QSlider",      "QMenu",         "QMenuBar",    "QToolBar",
                   "QStatusBar",     "QDockWidget",  "QMessageBox",   "QFileDialog", "QLayout",
                   "QVBoxLayout",    "QHBoxLayout",  "QGridLayout",   "QFormLayout", "QSplitter",
                   "QTabWidget",     "QTreeWidget",  "QListWidget",   "QTableView",  "QGroupBox",
                   "QOpenGLWidget",  "QScrollArea",  "QProgressBar",  "QToolButton", "qwidget.h",
                   "QDoubleSpinBox", "QHeaderView",  "QStackedWidget"};
    }
    return widgets;
}

QSet<QString> glFunctionsFromEpoxy(const QString& glGeneratedHeader) {
    QFile file(glGeneratedHeader);
    QSet<QString> names;
    if (!file.open(QIODevice::ReadOnly | QIODevice::Text)) {
        return names;
    }
    static const QRegularExpression define(QStringLiteral(R"(^#define (gl[A-Z]\w*) epoxy_)"),
                                           QRegularExpression::MultilineOption);
    const QString text = QString::fromUtf8(file.readAll());
    for (auto it = define.globalMatch(text); it.hasNext();) {
        names.insert(it.next().captured(1));
    }
    return names;
}

QString blankComments(const QString& text, bool blankLiterals) {
    QString out = text;
    const qsizetype n = text.size();
    auto blank = [&](qsizetype i) {
        if (out[i] != '\n') {
            out[i] = ' ';
        }
    };
    qsizetype i = 0;
    while (i < n) {
        const QChar c = text[i];
        const QChar next = i + 1 < n ? text[i + 1] : QChar();
        if (c == '/' && next == '/') {
            while (i < n && text[i] != '\n') {
                blank(i++);
            }
        } else if (c == '/' && next == '*') {
            blank(i++);
            blank(i++);
            while (i < n && !(text[i] == '*' && i + 1 < n && text[i + 1] == '/')) {
                blank(i++);
            }
            for (int k = 0; k < 2 && i < n; ++k) {
                blank(i++);
            }
        } else if (c == 'R' && next == '"' &&
                   (i == 0 || !isIdentifierChar(text[i - 1]) || text[i - 1] == 'L' ||
                    text[i - 1] == 'u' || text[i - 1] == 'U' || text[i - 1] == '8')) {
            // Raw string R"delim( ... )delim"
            const qsizetype open = text.indexOf('(', i + 2);
            if (open < 0) {
                ++i;
                continue;
            }
            const QString close = ')' + text.mid(i + 2, open - i - 2) + '"';
            qsizetype end = text.indexOf(close, open + 1);
            end = end < 0 ? n : end + close.size();
            for (qsizetype k = i + 2; k < end - 1 && blankLiterals; ++k) {
                blank(k);
            }
            i = end;
        } else if (c == '"' || (c == '\'' && (i == 0 || !isIdentifierChar(text[i - 1])))) {
            // A string or character literal ('\'' after a digit is a digit separator: 1'000).
            ++i;
            while (i < n && text[i] != c && text[i] != '\n') {
                if (text[i] == '\\' && i + 1 < n) {
                    if (blankLiterals) {
                        blank(i);
                    }
                    ++i;
                }
                if (blankLiterals) {
                    blank(i);
                }
                ++i;
            }
            ++i;
        } else {
            ++i;
        }
    }
    return out;
}

QList<Violation> checkFile(const QString& root, const QString& relPath, const QString& text,
                           const Config& config) {
    QList<Violation> out;

    static const QRegularExpression includeLine(
        QStringLiteral(R"re(^\s*#\s*include\s*(?:<([^>]+)>|"([^"]+)"))re"));
    const QStringList codeLines = blankComments(text, false).split('\n');
    for (qsizetype i = 0; i < codeLines.size(); ++i) {
        const QRegularExpressionMatch m = includeLine.match(codeLines[i]);
        if (m.hasMatch()) {
            const bool quoted = m.capturedLength(2) > 0;
            checkInclude(root, relPath, int(i) + 1, quoted ? m.captured(2) : m.captured(1), quoted,
                         config, out);
        }
    }

    // (2) GL calls: render/ only.
    if (firstComponent(relPath) != "render") {
        static const QRegularExpression glCall(QStringLiteral(R"(\b(gl[A-Z][A-Za-z0-9_]*)\s*\()"));
        const QStringList bareLines = blankComments(text, true).split('\n');
        for (qsizetype i = 0; i < bareLines.size(); ++i) {
            for (auto it = glCall.globalMatch(bareLines[i]); it.hasNext();) {
                const QString name = it.next().captured(1);
                if (config.glFunctions.isEmpty() || config.glFunctions.contains(name)) {
                    out << make(relPath, int(i) + 1, name + "()", Rule::Gl,
                                QStringLiteral("gl: GL calls only in render/"));
                }
            }
        }
    }

    std::stable_sort(out.begin(), out.end(),
                     [](const Violation& a, const Violation& b) { return a.line < b.line; });
    return out;
}

Report checkTree(const QString& root, const Config& config) {
    Report report;
    static const QStringList sourceSuffixes = {"h", "hpp", "cpp", "cc"};
    QStringList files;
    for (const QString& folder : kSourceFolders) {
        QDirIterator it(root + '/' + folder, QDir::Files, QDirIterator::Subdirectories);
        while (it.hasNext()) {
            const QFileInfo info(it.next());
            if (sourceSuffixes.contains(info.suffix())) {
                files << QDir(root).relativeFilePath(info.filePath());
            }
        }
    }
    files.sort();
    for (const QString& relPath : files) {
        QFile file(root + '/' + relPath);
        if (!file.open(QIODevice::ReadOnly)) {
            report.unreadable << relPath;
            continue;
        }
        report.violations << checkFile(root, relPath, QString::fromUtf8(file.readAll()), config);
        ++report.filesChecked;
    }
    return report;
}

} // namespace lucent::arch
