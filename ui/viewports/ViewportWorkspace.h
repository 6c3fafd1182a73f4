#pragma once

#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include <QString>
#include <QWidget>

#include "core/hanging/HangingProtocol.h"
#include "core/volume/Volume.h"

class QLabel;
class QMenu;

namespace lucent {

class SeriesLibrary;
class SeriesSession;
class Viewport;
class ViewportGrid;
class ViewportLinks;
class ViewportRegistration;

// The multi-series reading area: a ViewportGrid whose viewports show any loaded
// series (SeriesLibrary) and move together through ViewportLinks, with a line
// above it naming the layout (or the hanging protocol) and the last link notice.
class ViewportWorkspace : public QWidget {
    Q_OBJECT

public:
    explicit ViewportWorkspace(QWidget* parent = nullptr);
    ~ViewportWorkspace() override;

    ViewportGrid* grid() const { return grid_; }
    SeriesLibrary* library() const { return library_; }
    ViewportLinks* links() const { return links_; }
    ViewportRegistration* registration() const { return registration_; }

    // Loads path's series (in the background unless loaded) and shows it in
    // `viewport` as `view`; a failure goes to message().
    void showSeries(Viewport* viewport, const QString& path, const QString& series,
                    ViewportView view);
    // The active viewport shows the series (its view kept; MPR views stay MPR).
    void showInActive(const QString& path, const QString& series);
    // Puts a volume loaded elsewhere into the library and the active viewport.
    void showVolume(std::shared_ptr<const Volume> volume, const QString& path,
                    const QString& series);

    // A place to go to in a series (a lesion measured there, for one).
    struct SeriesPoint {
        QString path; // where to load the series from when no viewport shows it
        QString seriesUid;
        glm::dvec3 point; // LPS mm
    };
    // Moves each series' crosshair to its point; a series no viewport shows goes into
    // the n-th viewport (the grid grows to 1xN when it has fewer), loaded first.
    void goTo(const std::vector<SeriesPoint>& points);

    // The layouts, link and "link here" actions, for the View menu.
    void fillMenu(QMenu* menu);
    // What the line above the grid names (a protocol's name, or the layout's).
    void setCaption(const QString& caption);
    // Sessions not shown are dropped beyond this many bytes of voxels (default 4 GiB).
    void setMemoryBudget(std::size_t bytes) { budget_ = bytes; }

signals:
    void message(const QString& text, int timeoutMs);
    // A series asked for is shown (the grid is complete when nothing is loading).
    void seriesShown(lucent::Viewport* viewport);

private:
    void trimLibrary();

    ViewportGrid* grid_;
    SeriesLibrary* library_;
    ViewportLinks* links_;
    ViewportRegistration* registration_;
    QLabel* caption_;
    std::size_t budget_ = std::size_t{4} << 30;
};

} // namespace lucent
