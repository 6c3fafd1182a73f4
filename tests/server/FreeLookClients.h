#pragma once
// For the free look tests: a session's presenter and followers as protocol
// clients (RemoteTestFixture.h), free look on, and a follower's own frames.

#include "tests/server/RemoteTestFixture.h"

namespace lucent::test {

// The presenter creates a session showing the server's only series at side x
// side (ct-bone, the CT default); its id, empty when it failed.
inline QString presentOnlySeries(RemoteTestClient& presenter, int side) {
    if (!presenter.waitConnected() || !presenter.authenticate()) {
        return {};
    }
    presenter.send({{"type", "session-create"}});
    const QString id = presenter.waitForText("session-created")["session"].toString();
    if (openOnlySeries(presenter, side).isEmpty() || presenter.waitForText("opened").isEmpty() ||
        !presenter.waitForCurrentFrame()) {
        return {};
    }
    return id;
}

inline bool join(RemoteTestClient& follower, const QString& session) {
    if (!follower.waitConnected() || !follower.authenticate()) {
        return false;
    }
    follower.send({{"type", "session-join"}, {"session", session}});
    return !follower.waitForText("opened").isEmpty();
}

// Waits until the client holds more than `count` frames; the one at `count`, or null.
inline const ReceivedFrame* frameAfter(RemoteTestClient& client, qsizetype count) {
    (void)QTest::qWaitFor([&] { return client.frames.size() > count; }, 60000);
    return client.frames.size() > count ? &client.frames[count] : nullptr;
}

// Free look on: the seq its first own frame carries; -1 when refused.
inline qint64 startFreeLook(RemoteTestClient& follower) {
    const qsizetype from = follower.texts.size();
    follower.send({{"type", "free-look"}, {"state", "start"}});
    const QJsonObject started = follower.waitForText("free-look-started", 20000, from);
    if (started.isEmpty()) {
        return -1;
    }
    follower.seq = std::uint64_t(started["seq"].toInteger());
    return qint64(follower.seq);
}

// The lossless still of the follower's own latest change (its own seq), waited
// for: a busy server may send a cheaper frame of it first (then nothing more is owed).
inline const ReceivedFrame* settledFrame(RemoteTestClient& follower) {
    (void)QTest::qWaitFor(
        [&] {
            return !follower.frames.isEmpty() &&
                   follower.frames.back().header.seq == follower.seq &&
                   follower.frames.back().header.format == "png";
        },
        60000);
    const ReceivedFrame* last = follower.frames.isEmpty() ? nullptr : &follower.frames.back();
    return last && last->header.seq == follower.seq && last->header.format == "png" ? last
                                                                                    : nullptr;
}

inline const ReceivedFrame* ownFrame(RemoteTestClient& follower, const QJsonObject& change) {
    follower.change(change);
    return settledFrame(follower);
}

} // namespace lucent::test
