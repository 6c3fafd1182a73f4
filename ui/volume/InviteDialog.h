#pragma once
// "Invite Students...": the workstation presents its remote 3D view as a
// teaching session and hands out invites to it: a join link (copied with a
// button) and its QR code for the lecture hall's screen, when it expires, and
// revoke. An invite lets a student only follow this session, on the
// de-identified copy (docs/protocol.md, "Invites"), and look around on their
// own (free look): the dialog says how many do and brings everyone back.

#include <QDialog>

#include <cstdint>

#include "protocol/ServerMessages.h"

class QComboBox;
class QLabel;
class QLineEdit;
class QPushButton;

namespace lucent {

class QrCodeView;
class RemoteRenderBackend;

class InviteDialog : public QDialog {
    Q_OBJECT
public:
    explicit InviteDialog(RemoteRenderBackend& backend, QWidget* parent = nullptr);

    QPushButton* presentButton() const { return present_; }
    QPushButton* inviteButton() const { return invite_; }
    QPushButton* copyButton() const { return copy_; }
    QPushButton* revokeButton() const { return revoke_; }
    QComboBox* lifetimePicker() const { return lifetime_; }
    QLineEdit* linkEdit() const { return link_; }
    QrCodeView* qrView() const { return qr_; }
    QLabel* statusLabel() const { return status_; }
    QLabel* freeLookLabel() const { return freeLook_; }
    QPushButton* recallButton() const { return recall_; }

private:
    void showSession();
    void showInvite(const remote::InviteCreated& invite);
    void clearInvite(const QString& why);
    void showFreeLook(int looking);

    RemoteRenderBackend& backend_;
    QLabel* status_;
    QPushButton* present_;
    QComboBox* lifetime_;
    QPushButton* invite_;
    QLineEdit* link_;
    QPushButton* copy_;
    QrCodeView* qr_;
    QLabel* expiry_;
    QPushButton* revoke_;
    QLabel* freeLook_;
    QPushButton* recall_;
    std::uint64_t shown_ = 0; // the invite on screen
};

} // namespace lucent
