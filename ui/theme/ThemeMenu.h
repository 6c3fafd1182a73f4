#pragma once

class QMenu;

namespace lucent {

// A "Theme" submenu of `menu` with Dark and Light (checkable, one of them): a
// choice applies at once to the whole application and is saved (saveTheme).
// The actions' data is the theme's name.
QMenu* addThemeMenu(QMenu* menu);

} // namespace lucent
