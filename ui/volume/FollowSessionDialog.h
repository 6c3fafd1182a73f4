#pragma once
// "Follow a Session...": the workstation joins a teaching session that someone
// else presents, by its join link (https://HOST:PORT/#invite=CODE) or by the
// server's address, a token and the session's id; the 3D view then shows the
// session's frames with its pointer and marks. "Look Around" gives the view its
// own camera (free look), "Back to Teacher" the presenter's view again.
// Refusals (a bad link, a refused invite, the session's end) show in the
// dialog's status line.

#include <QDialog>

#include "render/SessionFollow.h"

class QLabel;
class QLineEdit;
class QPushButton;

namespace lucent {

class RemoteRenderBackend;

class FollowSessionDialog : public QDialog {
    Q_OBJECT
public:
    explicit FollowSessionDialog(RemoteRenderBackend& backend, QWidget* parent = nullptr);

    QLineEdit* linkEdit() const { return link_; }
    QLineEdit* sessionEdit() const { return session_; }
    QLineEdit* tokenEdit() const { return token_; }
    QPushButton* followButton() const { return follow_; }
    QPushButton* lookAroundButton() const { return lookAround_; }
    QPushButton* backButton() const { return back_; }
    QLabel* statusLabel() const { return status_; }

signals:
    // The view should follow this session (VolumeView::followSession).
    void followRequested(const lucent::SessionFollow& follow);

private:
    void requestFollow();
    void showState();

    RemoteRenderBackend& backend_;
    QLineEdit* link_;
    QLineEdit* session_;
    QLineEdit* token_;
    QPushButton* follow_;
    QPushButton* lookAround_;
    QPushButton* back_;
    QLabel* status_;
    QString frameProblem_; // the last refusal of the view (free look), until a frame comes
};

} // namespace lucent
