#pragma once
// Where the 3D view renders: the render server settings (URL, token, series)
// in a small dialog, kept with QSettings (group "renderServer"), and the View
// menu's "Render 3D on: This Computer / Server..." that switches the view.

#include <QDialog>

#include "render/RemoteRenderBackend.h"

class QComboBox;
class QLabel;
class QLineEdit;
class QMenu;
class QSettings;

namespace lucent {

class VolumeView;

// Keys renderServer/url, renderServer/token, renderServer/series.
RemoteServerSettings loadRenderServerSettings(const QSettings& settings);
void saveRenderServerSettings(QSettings& settings, const RemoteServerSettings& server);

class RenderServerSettings : public QDialog {
    Q_OBJECT

public:
    // offered: the series the server listed last time, to pick from.
    explicit RenderServerSettings(const RemoteServerSettings& initial,
                                  const std::vector<OfferedSeries>& offered = {},
                                  QWidget* parent = nullptr);

    RemoteServerSettings settings() const;
    // Accepts only usable settings; otherwise shows what is wrong, naming the field.
    void accept() override;

    QLineEdit* urlEdit() const { return url_; }
    QLineEdit* tokenEdit() const { return token_; }
    // Editable: a Series UID, or one the server offered; empty: the one loaded here.
    QComboBox* seriesPicker() const { return series_; }
    QLabel* problemLabel() const { return problem_; }

private:
    QLineEdit* url_;
    QLineEdit* token_;
    QComboBox* series_;
    QLabel* seriesNote_;
    QLabel* problem_;
};

// Adds "Render 3D on" to menu: "This Computer" and "Server..." (the dialog, then
// the switch; the settings are kept in the application's QSettings). The checked
// item follows the view. Then "Invite Students..." (InviteDialog), while the view
// renders on a server, and "Follow a Session..." (FollowSessionDialog).
void addRenderBackendMenu(QMenu* menu, VolumeView* view);

} // namespace lucent
