#include "ui/volume/FollowSessionDialog.h"

#include <QDialogButtonBox>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QLineEdit>
#include <QPushButton>
#include <QVBoxLayout>

#include "render/RemoteRenderBackend.h"

namespace lucent {

FollowSessionDialog::FollowSessionDialog(RemoteRenderBackend& backend, QWidget* parent)
    : QDialog(parent), backend_(backend), link_(new QLineEdit(this)), session_(new QLineEdit(this)),
      token_(new QLineEdit(this)), follow_(new QPushButton(tr("&Follow"), this)),
      lookAround_(new QPushButton(tr("&Look Around"), this)),
      back_(new QPushButton(tr("&Back to Teacher"), this)), status_(new QLabel(this)) {
    setWindowTitle(tr("Follow a Session"));
    link_->setPlaceholderText(tr("https://host:port/#invite=... (or the server's address)"));
    session_->setPlaceholderText(tr("only without an invite: the session's id"));
    token_->setPlaceholderText(tr("only without an invite: a token of the server"));
    token_->setEchoMode(QLineEdit::Password);
    status_->setWordWrap(true);
    auto* form = new QFormLayout;
    form->addRow(tr("Join link:"), link_);
    form->addRow(tr("Session:"), session_);
    form->addRow(tr("Token:"), token_);
    auto* row = new QHBoxLayout;
    row->addWidget(follow_);
    row->addWidget(lookAround_);
    row->addWidget(back_);
    auto* buttons = new QDialogButtonBox(QDialogButtonBox::Close, this);
    auto* layout = new QVBoxLayout(this);
    layout->addLayout(form);
    layout->addLayout(row);
    layout->addWidget(status_);
    layout->addWidget(buttons);
    connect(buttons, &QDialogButtonBox::rejected, this, &QDialog::reject);
    connect(follow_, &QPushButton::clicked, this, &FollowSessionDialog::requestFollow);
    connect(lookAround_, &QPushButton::clicked, this, [this] { backend_.lookAround(); });
    connect(back_, &QPushButton::clicked, this, [this] { backend_.backToTeacher(); });
    connect(&backend_, &RemoteRenderBackend::followStateChanged, this,
            &FollowSessionDialog::showState);
    connect(&backend_, &RenderBackend::statusChanged, this, &FollowSessionDialog::showState);
    connect(&backend_, &RenderBackend::frameFailed, this, [this](const QString& why) {
        frameProblem_ = why;
        showState();
    });
    connect(&backend_, &RenderBackend::frameReady, this, [this] {
        if (!frameProblem_.isEmpty()) {
            frameProblem_.clear();
            showState();
        }
    });
    showState();
}

void FollowSessionDialog::requestFollow() {
    frameProblem_.clear();
    QString why;
    std::optional<SessionFollow> follow;
    if (session_->text().trimmed().isEmpty()) {
        follow = SessionFollow::fromLink(link_->text(), &why);
    } else {
        // By token: the link is the server's address (https:// as the browser's, or ws://).
        QUrl server(link_->text().trimmed());
        server.setFragment({});
        server.setScheme(server.scheme() == "https"  ? "wss"
                         : server.scheme() == "http" ? "ws"
                                                     : server.scheme());
        follow = SessionFollow{server, {}, token_->text(), session_->text().trimmed()};
        why = follow->problem();
    }
    if (!follow || !why.isEmpty()) {
        status_->setText(tr("Cannot follow: %1").arg(why));
        return;
    }
    emit followRequested(*follow);
    showState();
}

void FollowSessionDialog::showState() {
    const FollowState state = backend_.followState();
    lookAround_->setEnabled(state == FollowState::Following);
    back_->setEnabled(state == FollowState::LookingAround);
    QString line;
    switch (state) {
    case FollowState::NotFollowing:
        line = backend_.status() == BackendStatus::Failed
                   ? tr("Cannot follow: %1").arg(backend_.statusMessage())
                   : tr("Not following a session.");
        break;
    case FollowState::Joining:
        line = tr("Joining: %1").arg(backend_.statusMessage());
        break;
    case FollowState::Following:
        line = tr("Following the teacher's view (%1).").arg(backend_.statusMessage());
        break;
    case FollowState::LookingAround:
        line = tr("Looking around on your own; Back to Teacher shows the teacher's view.");
        break;
    }
    if (!frameProblem_.isEmpty()) {
        line += "\n" + frameProblem_;
    }
    status_->setText(line);
}

} // namespace lucent
