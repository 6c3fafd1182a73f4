#include "ui/volume/RenderServerSettings.h"

#include <QActionGroup>
#include <QComboBox>
#include <QDialogButtonBox>
#include <QFormLayout>
#include <QLabel>
#include <QLineEdit>
#include <QMenu>
#include <QSettings>
#include <QVBoxLayout>

#include "ui/theme/Theme.h"
#include "ui/volume/FollowSessionDialog.h"
#include "ui/volume/InviteDialog.h"
#include "ui/volume/VolumeView.h"

namespace lucent {

RemoteServerSettings loadRenderServerSettings(const QSettings& settings) {
    RemoteServerSettings server;
    server.url = QUrl(settings.value("renderServer/url").toString());
    server.token = settings.value("renderServer/token").toString();
    server.series = settings.value("renderServer/series").toString();
    return server;
}

void saveRenderServerSettings(QSettings& settings, const RemoteServerSettings& server) {
    settings.setValue("renderServer/url", server.url.toString());
    settings.setValue("renderServer/token", server.token);
    settings.setValue("renderServer/series", server.series);
}

RenderServerSettings::RenderServerSettings(const RemoteServerSettings& initial,
                                           const std::vector<OfferedSeries>& offered,
                                           QWidget* parent)
    : QDialog(parent), url_(new QLineEdit(initial.url.toString(), this)),
      token_(new QLineEdit(initial.token, this)), series_(new QComboBox(this)),
      seriesNote_(new QLabel(this)), problem_(new QLabel(this)) {
    setWindowTitle(tr("Render Server"));
    url_->setPlaceholderText(QStringLiteral("ws://render-host:8765/"));
    token_->setEchoMode(QLineEdit::Password);
    token_->setPlaceholderText(tr("one line of the server's token file"));
    series_->setEditable(true);
    series_->setInsertPolicy(QComboBox::NoInsert);
    series_->addItem(QString());
    for (const OfferedSeries& s : offered) {
        series_->addItem(s.uid);
        series_->setItemData(series_->count() - 1,
                             tr("%1 %2, %3 x %4 x %5")
                                 .arg(s.modality, s.description)
                                 .arg(s.dims.x)
                                 .arg(s.dims.y)
                                 .arg(s.dims.z),
                             Qt::ToolTipRole);
    }
    series_->setCurrentText(initial.series);
    series_->lineEdit()->setPlaceholderText(tr("empty: the series loaded here"));
    const auto describe = [this] {
        const int at = series_->findText(series_->currentText());
        seriesNote_->setText(at > 0 ? series_->itemData(at, Qt::ToolTipRole).toString()
                                    : QString());
    };
    connect(series_, &QComboBox::currentTextChanged, this, describe);
    describe();
    problem_->setStyleSheet(statusStyleSheet(StatusTone::Warning));
    problem_->setWordWrap(true);
    auto* form = new QFormLayout;
    form->addRow(tr("Server &URL:"), url_);
    form->addRow(tr("&Token:"), token_);
    form->addRow(tr("&Series UID:"), series_);
    form->addRow(QString(), seriesNote_);
    auto* buttons = new QDialogButtonBox(QDialogButtonBox::Ok | QDialogButtonBox::Cancel, this);
    connect(buttons, &QDialogButtonBox::accepted, this, &RenderServerSettings::accept);
    connect(buttons, &QDialogButtonBox::rejected, this, &RenderServerSettings::reject);
    auto* layout = new QVBoxLayout(this);
    layout->addLayout(form);
    layout->addWidget(problem_);
    layout->addWidget(buttons);
}

RemoteServerSettings RenderServerSettings::settings() const {
    RemoteServerSettings s;
    s.url = QUrl(url_->text().trimmed(), QUrl::StrictMode);
    s.token = token_->text().trimmed();
    s.series = series_->currentText().trimmed();
    return s;
}

void RenderServerSettings::accept() {
    const QString problem = settings().problem();
    problem_->setText(problem);
    if (problem.isEmpty()) {
        QDialog::accept();
    }
}

void addRenderBackendMenu(QMenu* menu, VolumeView* view) {
    QMenu* where = menu->addMenu(QObject::tr("&Render 3D on"));
    auto* group = new QActionGroup(where);
    QAction* local = where->addAction(QObject::tr("This &Computer"));
    QAction* server = where->addAction(QObject::tr("&Server..."));
    for (QAction* action : {local, server}) {
        action->setCheckable(true);
        group->addAction(action);
    }
    const auto follow = [view, local, server] {
        (view->backend() == VolumeView::Backend::Remote ? server : local)->setChecked(true);
    };
    follow();
    QObject::connect(view, &VolumeView::backendChanged, where, follow);
    QObject::connect(local, &QAction::triggered, view, [view] { view->renderLocally(); });
    QObject::connect(server, &QAction::triggered, view, [view, follow] {
        QSettings settings;
        RenderServerSettings dialog(loadRenderServerSettings(settings),
                                    view->remoteBackend().offeredSeries(), view->window());
        if (dialog.exec() == QDialog::Accepted) {
            saveRenderServerSettings(settings, dialog.settings());
            view->renderOnServer(dialog.settings());
        }
        follow(); // cancelled: back to where the view still renders
    });
    // Teaching: the server's view presented as a session, with invites to it.
    QAction* invite = menu->addAction(QObject::tr("&Invite Students..."));
    invite->setObjectName(QStringLiteral("inviteStudents"));
    const auto enable = [view, invite] {
        invite->setEnabled(view->backend() == VolumeView::Backend::Remote);
    };
    enable();
    QObject::connect(view, &VolumeView::backendChanged, invite, enable);
    QObject::connect(invite, &QAction::triggered, view, [view] {
        auto* dialog = new InviteDialog(view->remoteBackend(), view->window());
        dialog->setAttribute(Qt::WA_DeleteOnClose); // modeless: the view stays in reach
        dialog->show();
    });
    // Teaching, the other side: the view follows a session someone else presents.
    QAction* followAction = menu->addAction(QObject::tr("&Follow a Session..."));
    followAction->setObjectName(QStringLiteral("followSession"));
    QObject::connect(followAction, &QAction::triggered, view, [view] {
        auto* dialog = new FollowSessionDialog(view->remoteBackend(), view->window());
        dialog->setAttribute(Qt::WA_DeleteOnClose); // modeless: the view stays in reach
        QObject::connect(dialog, &FollowSessionDialog::followRequested, view,
                         &VolumeView::followSession);
        dialog->show();
    });
}

} // namespace lucent
