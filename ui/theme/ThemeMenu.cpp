#include "ui/theme/ThemeMenu.h"

#include <QActionGroup>
#include <QApplication>
#include <QMenu>

#include "ui/theme/Theme.h"

namespace lucent {

QMenu* addThemeMenu(QMenu* menu) {
    QMenu* themes = menu->addMenu(QObject::tr("&Theme"));
    auto* group = new QActionGroup(themes);
    for (const auto& [theme, text] : {std::pair{Theme::Dark, QObject::tr("&Dark (reading room)")},
                                      std::pair{Theme::Light, QObject::tr("&Light")}}) {
        QAction* action = themes->addAction(text);
        action->setCheckable(true);
        action->setChecked(theme == currentTheme());
        action->setData(themeName(theme));
        group->addAction(action);
        QObject::connect(action, &QAction::triggered, themes, [theme = theme] {
            applyTheme(*qApp, theme);
            saveTheme(theme);
        });
    }
    // Another window or a restore may have changed the theme since.
    QObject::connect(themes, &QMenu::aboutToShow, themes, [group] {
        for (QAction* action : group->actions()) {
            action->setChecked(action->data().toString() == themeName(currentTheme()));
        }
    });
    return themes;
}

} // namespace lucent
