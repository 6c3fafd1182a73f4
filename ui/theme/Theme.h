#pragma once
// The workstation's look: Qt's Fusion style with a palette, dark by default for
// reading rooms (dark greys, not black, for panels; soft light grey text, not
// white, to keep glare down) or light. The image views keep black backgrounds
// in both. Widgets that paint themselves take their colours from the palette,
// and status texts from statusColour(), so that both themes read well.

#include <optional>

#include <QColor>
#include <QPalette>
#include <QString>

class QApplication;

namespace lucent {

enum class Theme { Dark, Light };

// "dark" or "light": the settings value.
QString themeName(Theme theme);
std::optional<Theme> themeFromName(const QString& name);

QPalette themePalette(Theme theme);

// Fusion style and the theme's palette for the whole application.
void applyTheme(QApplication& app, Theme theme);
// The theme applyTheme set last (Dark before any).
Theme currentTheme();

// The theme in the application's QSettings ("view/theme"; Dark when unset).
Theme savedTheme();
void saveTheme(Theme theme);

// Colours for status texts (errors, successes, warnings) that read on the
// palette's window and base colours: bright and soft on a dark palette, deep on
// a light one.
enum class StatusTone { Error, Ok, Warning };
QColor statusColour(StatusTone tone, const QPalette& palette);
// The same for the application's palette now, as a style sheet ("color: #rrggbb").
QString statusStyleSheet(StatusTone tone);

} // namespace lucent
