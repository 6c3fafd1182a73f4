#include "ui/viewports/ViewportWorkspace.h"

#include <set>

#include <QActionGroup>
#include <QLabel>
#include <QMenu>
#include <QPointer>
#include <QVBoxLayout>

#include "ui/mpr/MprCursor.h"
#include "ui/viewports/RegistrationExport.h"
#include "ui/viewports/SeriesLibrary.h"
#include "ui/viewports/SeriesSession.h"
#include "ui/viewports/Viewport.h"
#include "ui/viewports/ViewportGrid.h"
#include "ui/viewports/ViewportLinks.h"
#include "ui/viewports/ViewportRegistration.h"

namespace lucent {

ViewportWorkspace::ViewportWorkspace(QWidget* parent)
    : QWidget(parent), grid_(new ViewportGrid(this)), library_(new SeriesLibrary(this)),
      links_(new ViewportLinks(grid_, this)),
      registration_(new ViewportRegistration(grid_, links_, this)), caption_(new QLabel(this)) {
    auto* column = new QVBoxLayout(this);
    column->setContentsMargins(0, 0, 0, 0);
    column->setSpacing(0);
    caption_->setObjectName(QStringLiteral("viewportCaption"));
    caption_->setContentsMargins(6, 2, 6, 2);
    column->addWidget(caption_);
    column->addWidget(grid_, 1);
    setCaption(grid_->shape().name);
    connect(grid_, &ViewportGrid::seriesDropped, this,
            [this](Viewport* viewport, const QString& path, const QString& series) {
                const ViewportView view =
                    viewport->session() != nullptr && viewport->view() != ViewportView::Stack
                        ? viewport->view()
                        : ViewportView::Axial;
                showSeries(viewport, path, series, view);
            });
    connect(links_, &ViewportLinks::notice, this,
            [this](const QString& text) { emit message(text, 8000); });
    connect(registration_, &ViewportRegistration::progress, this,
            [this](const QString& text) { emit message(text, 0); });
    connect(registration_, &ViewportRegistration::finished, this,
            [this](bool, const QString& text) { emit message(text, 10000); });
    connect(library_, &SeriesLibrary::notice, this,
            [this](const QString& text) { emit message(text, 15000); });
    connect(library_, &SeriesLibrary::failed, this,
            [this](const QString& path, const QString&, const QString& error) {
                emit message(tr("Could not load %1: %2").arg(path, error), 10000);
            });
}

ViewportWorkspace::~ViewportWorkspace() = default;

void ViewportWorkspace::setCaption(const QString& caption) {
    caption_->setText(caption);
}

void ViewportWorkspace::showSeries(Viewport* viewport, const QString& path, const QString& series,
                                   ViewportView view) {
    if (viewport == nullptr) {
        return;
    }
    QPointer<Viewport> target(viewport);
    // The newest request for a viewport wins; an older one arriving later is dropped.
    viewport->setProperty("wantedSeries", path + QLatin1Char('\n') + series);
    auto connection = std::make_shared<QMetaObject::Connection>();
    *connection = connect(library_, &SeriesLibrary::ready, this,
                          [this, target, path, series, view,
                           connection](const QString& p, const QString& s, SeriesSession* session) {
                              if (p != path || s != series) {
                                  return;
                              }
                              disconnect(*connection);
                              if (target.isNull() || target->property("wantedSeries").toString() !=
                                                         path + QLatin1Char('\n') + series) {
                                  return;
                              }
                              target->show(session, view);
                              trimLibrary();
                              emit seriesShown(target);
                          });
    library_->request(path, series);
}

void ViewportWorkspace::showInActive(const QString& path, const QString& series) {
    Viewport* active = grid_->activeViewport();
    if (active == nullptr) {
        return;
    }
    const ViewportView view = active->session() != nullptr ? active->view() : ViewportView::Axial;
    showSeries(active, path, series, view);
}

void ViewportWorkspace::showVolume(std::shared_ptr<const Volume> volume, const QString& path,
                                   const QString& series) {
    SeriesSession* session = library_->adopt(std::move(volume), path, series);
    if (Viewport* active = grid_->activeViewport()) {
        active->setProperty("wantedSeries", QVariant());
        active->show(session, active->session() != nullptr ? active->view() : ViewportView::Axial);
        emit seriesShown(active);
    }
}

void ViewportWorkspace::goTo(const std::vector<SeriesPoint>& points) {
    const int needed = static_cast<int>(points.size());
    if (grid_->count() < needed) {
        grid_->setShape(regularGridShape(1, needed));
        setCaption(grid_->shape().name);
    }
    for (int n = 0; n < needed; ++n) {
        const SeriesPoint& where = points[static_cast<std::size_t>(n)];
        Viewport* showing = nullptr;
        for (Viewport* v : grid_->viewports()) {
            if (v->session() != nullptr && v->session()->seriesUid() == where.seriesUid) {
                showing = v;
                break;
            }
        }
        if (showing != nullptr) {
            showing->session()->cursor()->setPoint(where.point);
            continue;
        }
        Viewport* target = grid_->viewport(n);
        auto connection = std::make_shared<QMetaObject::Connection>();
        *connection = connect(this, &ViewportWorkspace::seriesShown, this,
                              [target, where, connection](Viewport* shown) {
                                  if (shown != target || shown->session() == nullptr) {
                                      return;
                                  }
                                  disconnect(*connection);
                                  shown->session()->cursor()->setPoint(where.point);
                              });
        showSeries(target, where.path, where.seriesUid, ViewportView::Axial);
    }
}

void ViewportWorkspace::trimLibrary() {
    std::set<const SeriesSession*> shown;
    for (const Viewport* v : grid_->viewports()) {
        if (v->session() != nullptr) {
            shown.insert(v->session());
        }
    }
    if (const int dropped = library_->trim(shown, budget_); dropped > 0) {
        emit message(tr("%n series not shown dropped from memory (opened again on demand)", nullptr,
                        dropped),
                     5000);
    }
}

void ViewportWorkspace::fillMenu(QMenu* menu) {
    auto* shapes = new QActionGroup(menu);
    for (const GridShape& shape : standardGridShapes()) {
        QAction* action = menu->addAction(tr("Grid %1").arg(shape.name));
        action->setCheckable(true);
        action->setObjectName(QStringLiteral("grid-%1").arg(shape.name));
        shapes->addAction(action);
        connect(action, &QAction::triggered, this, [this, shape] {
            grid_->setShape(shape);
            setCaption(shape.name);
        });
    }
    menu->addSeparator();
    menu->addAction(tr("&Link or Unlink Active Viewport"), QKeySequence(tr("Ctrl+L")), this,
                    [this] {
                        if (Viewport* v = grid_->activeViewport()) {
                            v->toggleLink();
                        }
                    });
    menu->addAction(tr("Link &All Viewports"), QKeySequence(tr("Ctrl+Shift+L")), this,
                    [this] { links_->linkAll(1); });
    menu->addAction(tr("&Unlink All Viewports"), this, [this] { links_->linkAll(0); });
    menu->addAction(tr("Link &Here (same anatomy under each crosshair)"),
                    QKeySequence(tr("Ctrl+Alt+L")), this,
                    [this] { links_->linkHere(grid_->activeViewport()); });
    menu->addAction(tr("&Register Linked Viewports to Active"), QKeySequence(tr("Ctrl+Alt+R")),
                    this, [this] { registration_->registerWith(grid_->activeViewport()); });
    menu->addAction(tr("Cancel Registration"), this, [this] { registration_->cancel(); });
    menu->addAction(tr("Save Registrations to the Study Store (DICOM)"), this, [this] {
        QString text;
        saveRegistrations(*this, grid_->activeViewport(), &text);
        emit message(text, 10000);
    });
}

} // namespace lucent
