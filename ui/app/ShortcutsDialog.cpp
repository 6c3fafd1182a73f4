#include "ui/app/ShortcutsDialog.h"

#include <functional>

#include <QDialogButtonBox>
#include <QHeaderView>
#include <QMenu>
#include <QMenuBar>
#include <QRegularExpression>
#include <QTableWidget>
#include <QVBoxLayout>

#include "ui/mpr/SliceTools.h"

namespace lucent {

namespace {

QString withoutMnemonic(QString text) {
    return text.remove(QRegularExpression(QStringLiteral("&(?!&)"))).section('\t', 0, 0);
}

} // namespace

ShortcutsDialog::ShortcutsDialog(const QMenuBar& menus, QWidget* parent)
    : QDialog(parent), table_(new QTableWidget(0, 3, this)) {
    setObjectName(QStringLiteral("shortcutsDialog"));
    setWindowTitle(tr("Keyboard Shortcuts"));
    table_->setObjectName(QStringLiteral("shortcutsTable"));
    table_->setHorizontalHeaderLabels({tr("Where"), tr("Keys"), tr("What")});
    table_->verticalHeader()->hide();
    table_->setEditTriggers(QAbstractItemView::NoEditTriggers);
    table_->horizontalHeader()->setStretchLastSection(true);

    const QString tools = tr("MPR tools");
    for (const SliceToolInfo& info : sliceTools()) {
        addRow(tools, QString::fromLatin1(info.key),
               QStringLiteral("%1: %2").arg(QString::fromLatin1(info.name),
                                            QString::fromLatin1(info.help)));
    }
    const QString views = tr("MPR views");
    for (const SliceKeyInfo& key : sliceViewKeys()) {
        addRow(views, QString::fromLatin1(key.keys), QString::fromLatin1(key.what));
    }
    // Every menu's actions with a shortcut, submenus included.
    std::function<void(const QMenu&, const QString&)> walk = [&](const QMenu& menu,
                                                                 const QString& where) {
        for (const QAction* action : menu.actions()) {
            if (action->menu() != nullptr) {
                walk(*action->menu(), where + " > " + withoutMnemonic(action->text()));
            } else if (!action->shortcuts().isEmpty()) {
                QStringList keys;
                for (const QKeySequence& key : action->shortcuts()) {
                    keys << key.toString(QKeySequence::NativeText);
                }
                addRow(where, keys.join(QStringLiteral(", ")), withoutMnemonic(action->text()));
            }
        }
    };
    for (const QAction* action : menus.actions()) {
        if (action->menu() != nullptr) {
            walk(*action->menu(), withoutMnemonic(action->text()));
        }
    }
    table_->resizeColumnsToContents();

    auto* buttons = new QDialogButtonBox(QDialogButtonBox::Close, this);
    connect(buttons, &QDialogButtonBox::rejected, this, &QDialog::reject);
    auto* column = new QVBoxLayout(this);
    column->addWidget(table_, 1);
    column->addWidget(buttons);
    resize(720, 560);
}

void ShortcutsDialog::addRow(const QString& section, const QString& keys, const QString& what) {
    const int row = table_->rowCount();
    table_->insertRow(row);
    table_->setItem(row, 0, new QTableWidgetItem(section));
    table_->setItem(row, 1, new QTableWidgetItem(keys));
    table_->setItem(row, 2, new QTableWidgetItem(what));
}

} // namespace lucent
