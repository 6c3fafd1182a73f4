#include "ui/volume/InviteDialog.h"

#include <QClipboard>
#include <QComboBox>
#include <QDateTime>
#include <QDialogButtonBox>
#include <QFormLayout>
#include <QGuiApplication>
#include <QHBoxLayout>
#include <QLabel>
#include <QLineEdit>
#include <QPushButton>
#include <QVBoxLayout>

#include "render/RemoteRenderBackend.h"
#include "ui/volume/QrCodeView.h"

namespace lucent {

InviteDialog::InviteDialog(RemoteRenderBackend& backend, QWidget* parent)
    : QDialog(parent), backend_(backend), status_(new QLabel(this)),
      present_(new QPushButton(this)), lifetime_(new QComboBox(this)),
      invite_(new QPushButton(tr("&Create Invite"), this)), link_(new QLineEdit(this)),
      copy_(new QPushButton(tr("C&opy Link"), this)), qr_(new QrCodeView(this)),
      expiry_(new QLabel(this)), revoke_(new QPushButton(tr("&Revoke"), this)),
      freeLook_(new QLabel(this)), recall_(new QPushButton(tr("&Bring Everyone Back"), this)) {
    setWindowTitle(tr("Invite Students"));
    status_->setWordWrap(true);
    lifetime_->addItem(tr("Until the session ends (at most a day)"), 0);
    for (const int hours : {1, 2, 4}) {
        lifetime_->addItem(tr("%n hour(s)", nullptr, hours), hours * 3600);
    }
    link_->setReadOnly(true);
    link_->setPlaceholderText(tr("the join link"));
    auto* form = new QFormLayout;
    form->addRow(tr("Valid:"), lifetime_);
    auto* linkRow = new QHBoxLayout;
    linkRow->addWidget(link_, 1);
    linkRow->addWidget(copy_);
    auto* buttons = new QDialogButtonBox(QDialogButtonBox::Close, this);
    auto* layout = new QVBoxLayout(this);
    layout->addWidget(status_);
    layout->addWidget(present_);
    layout->addLayout(form);
    layout->addWidget(invite_);
    layout->addLayout(linkRow);
    layout->addWidget(qr_, 1);
    layout->addWidget(expiry_);
    layout->addWidget(revoke_);
    auto* freeLookRow = new QHBoxLayout;
    freeLookRow->addWidget(freeLook_, 1);
    freeLookRow->addWidget(recall_);
    layout->addLayout(freeLookRow);
    layout->addWidget(buttons);
    connect(buttons, &QDialogButtonBox::rejected, this, &QDialog::reject);

    connect(present_, &QPushButton::clicked, this,
            [this] { backend_.setPresenting(!backend_.presenting()); });
    connect(invite_, &QPushButton::clicked, this, [this] {
        const int seconds = lifetime_->currentData().toInt();
        backend_.createInvite(seconds > 0 ? std::optional<std::int64_t>(seconds) : std::nullopt);
    });
    connect(copy_, &QPushButton::clicked, this,
            [this] { QGuiApplication::clipboard()->setText(link_->text()); });
    connect(revoke_, &QPushButton::clicked, this, [this] { backend_.revokeInvite(shown_); });
    connect(recall_, &QPushButton::clicked, &backend_, &RemoteRenderBackend::recallFreeLook);
    connect(&backend_, &RemoteRenderBackend::freeLookChanged, this,
            [this](int looking) { showFreeLook(looking); });
    connect(&backend_, &RemoteRenderBackend::sessionChanged, this, [this] {
        clearInvite(backend_.presenting() && backend_.sessionId().isEmpty()
                        ? tr("The session ended with the connection: its invites are void.")
                        : QString());
        showSession();
    });
    connect(&backend_, &RemoteRenderBackend::statusChanged, this, &InviteDialog::showSession);
    connect(&backend_, &RemoteRenderBackend::inviteCreated, this, &InviteDialog::showInvite);
    connect(&backend_, &RemoteRenderBackend::inviteRevoked, this, [this](quint64 invite) {
        if (invite == shown_) {
            clearInvite(tr("Invite revoked: its link lets no one in, and its students were "
                           "dropped."));
        }
    });
    connect(&backend_, &RemoteRenderBackend::inviteRefused, this,
            [this](const QString& why) { expiry_->setText(why); });
    clearInvite({});
    showFreeLook(0);
    showSession();
}

void InviteDialog::showFreeLook(int looking) {
    freeLook_->setText(looking == 0
                           ? tr("Every student follows your view.")
                           : tr("%n student(s) look around on their own.", nullptr, looking));
    recall_->setEnabled(looking > 0);
}

void InviteDialog::showSession() {
    const bool presenting = backend_.presenting();
    const QString session = backend_.sessionId();
    present_->setText(presenting ? tr("&Stop Presenting") : tr("&Present to Students"));
    if (!presenting) {
        status_->setText(tr("The 3D view renders on %1. Present it as a teaching session to "
                            "invite students: they watch it, de-identified, and may look around "
                            "on their own, nothing else.")
                             .arg(backend_.settings().url.toDisplayString()));
    } else if (session.isEmpty()) {
        status_->setText(tr("Starting the session: %1").arg(backend_.statusMessage()));
    } else {
        status_->setText(tr("Presenting session %1.").arg(session));
    }
    invite_->setEnabled(!session.isEmpty());
    lifetime_->setEnabled(!session.isEmpty());
}

void InviteDialog::showInvite(const remote::InviteCreated& invite) {
    shown_ = invite.invite;
    link_->setText(QString::fromStdString(invite.link));
    qr_->setCode(invite.qr);
    expiry_->setText(tr("Valid until %1, or until the session ends.")
                         .arg(QDateTime::fromSecsSinceEpoch(invite.expires)
                                  .toString(QStringLiteral("yyyy-MM-dd HH:mm"))));
    copy_->setEnabled(true);
    revoke_->setEnabled(true);
}

void InviteDialog::clearInvite(const QString& why) {
    shown_ = 0;
    link_->clear();
    qr_->setCode({});
    expiry_->setText(why);
    copy_->setEnabled(false);
    revoke_->setEnabled(false);
}

} // namespace lucent
