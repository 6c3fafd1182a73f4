#pragma once
// The dependency rules of docs/DESIGN.md, checked on the source tree by reading it: which
// folder may include which, where GL, widgets and third-party headers may appear. Plain QtCore,
// no project library, so the check builds and runs without the code it checks.

#include <QList>
#include <QSet>
#include <QString>
#include <QStringList>

namespace lucent::arch {

// The layers, top to bottom; a folder may include its own and those it points to:
// app -> ui -> render -> protocol -> core, and app -> server -> render (server beside ui).
inline const QStringList kSourceFolders = {"core", "protocol", "render", "server", "ui", "app"};

enum class Rule {
    Layers,     // (1) a project include that points against the arrows
    Gl,         // (2) a GL header or a GL call outside render/ (GL headers also in ui/volume/)
    Widgets,    // (3) a Qt Widgets header outside ui/ and app/lucent/
    ThirdParty, // (4) a third-party header in a .h file of core/protocol/render/server/ui
};

// "layers", "gl", "widgets", "third-party".
QString ruleName(Rule rule);

struct Violation {
    QString file;    // relative to the root, '/' separators
    int line = 0;    // 1-based
    QString subject; // the include as written (#include <QWidget>) or the call (glClear()
    Rule rule = Rule::Layers;
    QString reason; // the rule broken, in words

    // "core/a.h:3: #include "render/b.h" -- layers: core/ may include only core/"
    QString toString() const;
};

struct Config {
    // Header names of the QtWidgets and QtOpenGLWidgets modules (QWidget, qwidget.h, ...),
    // without the compatibility headers that QtGui or QtCore also hold (QtGui's qaction.h).
    QSet<QString> widgetHeaders;
    // The GL entry points (glClear, ...). A gl[A-Z]...( call counts only when its name is one of
    // them, so a project function called glUnavailableReason() is not a GL call. Empty: every
    // gl[A-Z]...( call counts.
    QSet<QString> glFunctions;
};

// The widget headers of the Qt this test was built with (QLibraryInfo::HeadersPath); a fixed
// list of the common ones where those folders are missing.
QSet<QString> widgetHeadersFromQt();

// The names epoxy defines ("#define glClear epoxy_glClear") in its gl_generated.h; empty when
// the file cannot be read.
QSet<QString> glFunctionsFromEpoxy(const QString& glGeneratedHeader);

struct Report {
    QList<Violation> violations; // by file, then line
    int filesChecked = 0;
    QStringList unreadable; // files found but not read: the check is incomplete
};

// Walks kSourceFolders under root for .h/.hpp/.cpp/.cc files and checks each.
Report checkTree(const QString& root, const Config& config);

// One file: relPath is relative to root (core/volume/Volume.h), text its contents. root is used
// to resolve includes written relative to the file ("../render/x.h").
QList<Violation> checkFile(const QString& root, const QString& relPath, const QString& text,
                           const Config& config);

// The text with comments blanked (newlines kept, so lines and columns stay); string and character
// literals blanked too when blankLiterals.
QString blankComments(const QString& text, bool blankLiterals);

} // namespace lucent::arch
