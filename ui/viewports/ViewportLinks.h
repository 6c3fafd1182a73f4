#pragma once

#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <utility>

#include <QObject>
#include <QString>

#include <glm/glm.hpp>

#include "core/linking/SeriesLink.h"
#include "ui/viewports/StoredRegistrations.h"

namespace lucent {

class SeriesSession;
class StudyStore;
class Viewport;
class ViewportGrid;

// Links the viewports of a grid that share a link group (Viewport::linkGroup):
// moving the crosshair or scrolling in one moves the others of other series to the
// same anatomy (SeriesLink: the same position within a Frame of Reference, else a
// registration's transform or the "link here" offset kept in the study store), onto
// their nearest slice; window and
// level follow between series of one modality that showed the same window; zoom and
// pan between parallel MPR views. Planes more than kParallelToleranceDegrees apart do not scroll
// together, and a series pair with no known relation does not move: both say why in notice(). Every
// MPR viewport shows the planes of the other viewports it can place (same Frame of Reference or an
// offset) as reference lines.
class ViewportLinks : public QObject {
    Q_OBJECT

public:
    explicit ViewportLinks(ViewportGrid* grid, QObject* parent = nullptr);
    ~ViewportLinks() override;

    // The study store that keeps "link here" offsets; without one they last for the
    // session only.
    void setStoreFolder(const QString& folder);
    // The study store's folder ("" without one).
    QString storeFolder() const;

    // "Link here": the reader put the crosshair on the same anatomy in `viewport`
    // and in the other linked viewports; each of those whose series has another Frame
    // of Reference gets the offset between the two crosshairs, kept per pair. Returns
    // how many pairs were linked; `message` says what was done (or why nothing).
    int linkHere(Viewport* viewport, QString* message = nullptr);

    // A registration's transform from series a to series b (LPS mm): kept in the
    // store (or for the session without one); links the pair from now on.
    void setTransform(const std::string& a, const std::string& b, const glm::dmat4& aToB);
    std::optional<glm::dmat4> transform(const std::string& a, const std::string& b) const;

    // Reads the store's Spatial Registration objects again (after a study came in).
    void reloadStoredRegistrations();

    // The link between the series of two viewports, as it is now: a transform kept for
    // the pair, else one of the store's Spatial Registration objects relating their Frames
    // of Reference, else SeriesLink's other kinds.
    SeriesLink linkBetween(const SeriesSession& a, const SeriesSession& b) const;

    // Sets every viewport's link group (0: all unlinked).
    void linkAll(int group);

    const QString& lastNotice() const { return lastNotice_; }

signals:
    void notice(const QString& text);

private:
    void rewire();
    void pointMoved(SeriesSession* source);
    void windowChanged(SeriesSession* source);
    void zoomPanChanged(Viewport* source);
    void updateReferenceLines();
    Viewport* sourceViewport(SeriesSession* session, int group) const;
    std::optional<glm::dvec3> offset(const std::string& a, const std::string& b) const;
    void say(const QString& text);

    ViewportGrid* grid_;
    std::unique_ptr<StudyStore> store_;
    StoredRegistrations registrations_;
    std::map<std::pair<std::string, std::string>, glm::dvec3> sessionOffsets_; // without a store
    std::map<std::pair<std::string, std::string>, glm::dmat4> sessionTransforms_;
    std::map<const SeriesSession*, std::pair<double, double>> windows_; // last seen
    std::set<QString> said_; // notices given already (each once per session)
    QString lastNotice_;
    bool propagating_ = false;
    std::vector<QMetaObject::Connection> connections_;
};

} // namespace lucent
