#include "ui/theme/Theme.h"

#include <memory>

#include <QApplication>
#include <QSettings>
#include <QStyle>
#include <QStyleFactory>
#include <QWidget>

namespace lucent {

namespace {

const QString kThemeKey = QStringLiteral("view/theme");
Theme current = Theme::Dark;

QPalette darkPalette() {
    // Greys from about 12% (deep panels) to 22% (buttons); text at 83% grey.
    const QColor window(45, 45, 48);
    const QColor base(32, 32, 35);
    const QColor text(212, 212, 212);
    const QColor disabledText(125, 125, 128);
    QPalette p;
    p.setColor(QPalette::Window, window);
    p.setColor(QPalette::WindowText, text);
    p.setColor(QPalette::Base, base);
    p.setColor(QPalette::AlternateBase, QColor(40, 40, 43));
    p.setColor(QPalette::ToolTipBase, QColor(58, 58, 62));
    p.setColor(QPalette::ToolTipText, text);
    p.setColor(QPalette::PlaceholderText, QColor(135, 135, 138));
    p.setColor(QPalette::Text, text);
    p.setColor(QPalette::Button, QColor(56, 56, 60));
    p.setColor(QPalette::ButtonText, text);
    p.setColor(QPalette::BrightText, QColor(255, 128, 112));
    p.setColor(QPalette::Light, QColor(78, 78, 82));
    p.setColor(QPalette::Midlight, QColor(64, 64, 68));
    p.setColor(QPalette::Mid, QColor(38, 38, 41));
    p.setColor(QPalette::Dark, QColor(28, 28, 30));
    p.setColor(QPalette::Shadow, QColor(16, 16, 18));
    // A muted blue selection, its text lighter than the rest.
    p.setColor(QPalette::Highlight, QColor(48, 92, 150));
    p.setColor(QPalette::HighlightedText, QColor(236, 236, 236));
    p.setColor(QPalette::Link, QColor(110, 160, 230));
    p.setColor(QPalette::LinkVisited, QColor(160, 130, 220));
    for (const auto role : {QPalette::WindowText, QPalette::Text, QPalette::ButtonText}) {
        p.setColor(QPalette::Disabled, role, disabledText);
    }
    p.setColor(QPalette::Disabled, QPalette::Base, window);
    p.setColor(QPalette::Disabled, QPalette::Highlight, QColor(70, 70, 74));
    p.setColor(QPalette::Disabled, QPalette::HighlightedText, disabledText);
    return p;
}

// Fusion's light palette, not the platform's (the same on every desktop), with
// disabled text and the selection dark enough to read.
QPalette lightPalette() {
    const std::unique_ptr<QStyle> fusion(QStyleFactory::create(QStringLiteral("Fusion")));
    QPalette p = fusion ? fusion->standardPalette() : QPalette();
    p.setColor(QPalette::Highlight, QColor(38, 106, 176));
    p.setColor(QPalette::HighlightedText, Qt::white);
    for (const auto role : {QPalette::WindowText, QPalette::Text, QPalette::ButtonText}) {
        p.setColor(QPalette::Disabled, role, QColor(118, 118, 118));
    }
    return p;
}

bool isDark(const QPalette& palette) {
    return palette.color(QPalette::Window).lightness() < 128;
}

} // namespace

QString themeName(Theme theme) {
    return theme == Theme::Dark ? QStringLiteral("dark") : QStringLiteral("light");
}

std::optional<Theme> themeFromName(const QString& name) {
    if (name == QLatin1String("dark")) {
        return Theme::Dark;
    }
    if (name == QLatin1String("light")) {
        return Theme::Light;
    }
    return std::nullopt;
}

QPalette themePalette(Theme theme) {
    return theme == Theme::Dark ? darkPalette() : lightPalette();
}

void applyTheme(QApplication& app, Theme theme) {
    if (app.style()->name().compare(QLatin1String("fusion"), Qt::CaseInsensitive) != 0) {
        app.setStyle(QStyleFactory::create(QStringLiteral("Fusion")));
    }
    QApplication::setPalette(themePalette(theme));
    // Qt tells windows of the change through their native windows: a top-level
    // widget not shown yet (a main window still being built, a hidden dialog)
    // has none and would keep the old palette.
    for (QWidget* widget : QApplication::topLevelWidgets()) {
        if (widget->windowHandle() == nullptr) {
            QEvent change(QEvent::ApplicationPaletteChange);
            QCoreApplication::sendEvent(widget, &change);
        }
    }
    current = theme;
}

Theme currentTheme() {
    return current;
}

Theme savedTheme() {
    return themeFromName(QSettings().value(kThemeKey).toString()).value_or(Theme::Dark);
}

void saveTheme(Theme theme) {
    QSettings().setValue(kThemeKey, themeName(theme));
}

QColor statusColour(StatusTone tone, const QPalette& palette) {
    const bool dark = isDark(palette);
    switch (tone) {
    case StatusTone::Error:
        return dark ? QColor(240, 118, 104) : QColor(176, 28, 28);
    case StatusTone::Ok:
        return dark ? QColor(122, 200, 122) : QColor(24, 110, 40);
    case StatusTone::Warning:
        return dark ? QColor(230, 168, 84) : QColor(160, 72, 0);
    }
    return palette.color(QPalette::WindowText);
}

QString statusStyleSheet(StatusTone tone) {
    return QStringLiteral("color: %1").arg(statusColour(tone, QApplication::palette()).name());
}

} // namespace lucent
