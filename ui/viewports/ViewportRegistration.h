#pragma once

#include <memory>
#include <thread>
#include <vector>

#include <QObject>
#include <QString>

namespace lucent {

class Viewport;
class ViewportGrid;
class ViewportLinks;

// "Register": the series of a viewport and those of the other viewports of its link
// group that lie in another Frame of Reference are aligned rigidly (core/registration,
// Mattes MI) on worker threads, one pair after the other; each transform found is
// kept by ViewportLinks (in the store, per series pair), so scrolling, the crosshair
// and the reference lines land on the same anatomy from then on. A pair that cannot
// be registered says why; nothing is linked by a guess.
class ViewportRegistration : public QObject {
    Q_OBJECT

public:
    ViewportRegistration(ViewportGrid* grid, ViewportLinks* links, QObject* parent = nullptr);
    ~ViewportRegistration() override; // cancels and waits

    // Starts registering `viewport`'s series (fixed) with every other linked series of
    // another Frame of Reference (moving); returns how many pairs, `message` says which.
    // With `again` false, pairs that have a transform already are left as they are.
    int registerWith(Viewport* viewport, QString* message = nullptr, bool again = true);
    void cancel();
    int running() const { return running_; }

signals:
    void progress(const QString& text);
    // One pair done (ok: linked through the transform) or not, with what happened.
    void finished(bool ok, const QString& text);

private:
    ViewportGrid* grid_;
    ViewportLinks* links_;
    int running_ = 0;
    std::vector<std::jthread> workers_;
};

} // namespace lucent
