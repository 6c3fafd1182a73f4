#pragma once

#include <QDialog>

class QMenuBar;
class QTableWidget;

namespace lucent {

// Help > Keyboard Shortcuts: every key of the workstation in one table, made from
// where the keys are defined: the MPR tools (sliceTools()), the MPR view's other keys
// and mouse (sliceViewKeys()) and every menu action that has a shortcut.
class ShortcutsDialog : public QDialog {
    Q_OBJECT

public:
    ShortcutsDialog(const QMenuBar& menus, QWidget* parent = nullptr);
    QTableWidget* table() const { return table_; }

private:
    void addRow(const QString& section, const QString& keys, const QString& what);

    QTableWidget* table_;
};

} // namespace lucent
