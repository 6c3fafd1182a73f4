// The workstation following a teaching session on a real lucent-server (loopback,
// the demo head CT) that a RemoteTestClient presents, marks and points at: by the
// join link the frame is the presenter's, the mark is painted at its anchor's
// projection (2 px) and the pointer where sent, also after a 90 degree turn; Look
// Around, then Back to Teacher gives the presenter's frame again; the 3D view
// follows with no volume and looks around on a drag. Refusals: bad links, a revoked
// invite, no such session, the session's end. By token and id too. Offscreen.
#include <QApplication>
#include <QDir>
#include <QImage>
#include <QJsonArray>
#include <QLabel>
#include <QLineEdit>
#include <QPainter>
#include <QPushButton>
#include <QTest>

#include <filesystem>
#include <optional>

#include "core/formats/InVesaliusProject.h"
#include "core/image/ImageMetrics.h"
#include "core/scene/ImageProjection.h"
#include "core/scene/ViewFrame.h"
#include "render/RemoteRenderBackend.h"
#include "tests/server/DemoHead.h"
#include "tests/server/RemoteTestFixture.h"
#include "tests/support/OffscreenPlatform.h"
#include "ui/volume/FollowSessionDialog.h"
#include "ui/volume/TeachingMarksOverlay.h"
#include "ui/volume/VolumeView.h"

using namespace lucent;
using namespace lucent::test;

namespace {

constexpr int kSide = 128;
const QStringList kV4 = {"lucent.v4"};

QImage toQImage(const ImageRGBA8& f) {
    return QImage(f.pixels.data(), f.width, f.height, 4 * f.width, QImage::Format_RGBA8888).copy();
}

// The frame with the session's marks painted over it, as VolumeView paints them.
QImage painted(const BackendFrame& frame, const TeachingMarks& marks) {
    QImage out = toQImage(frame.image).convertToFormat(QImage::Format_RGB32);
    QPainter painter(&out);
    paintTeachingMarks(painter, QRectF(0, 0, out.width(), out.height()), marks, *frame.projection);
    return out;
}

bool near(const QColor& a, const QColor& b) {
    return std::abs(a.red() - b.red()) < 40 && std::abs(a.green() - b.green()) < 40 &&
           std::abs(a.blue() - b.blue()) < 40;
}

// PSNR in dB; -1 for images of different sizes.
double db(const ImageRGBA8& a, const ImageRGBA8& b) {
    return a.width == b.width && a.height == b.height && !a.pixels.empty() ? psnr(a, b) : -1.0;
}

// A comparison's verdict: under 50 dB the frame is saved for a look afterwards.
QString verdict(double got, const ImageRGBA8& image, const QString& name) {
    const QString path = QDir::temp().filePath(name + ".png");
    if (got < 50.0 && !image.pixels.empty()) {
        toQImage(image).save(path);
    }
    return QString("%1 dB against the presenter's frame (below 50: %2)").arg(got).arg(path);
}

// What a follower of the workstation saw.
struct Follower {
    QList<BackendFrame> frames;
    FollowState firstState = FollowState::NotFollowing; // the first it reported
    std::optional<Camera> lookedFrom;                   // lookAroundStarted's camera
    qsizetype followingFrom = 0; // the first frame since the state became Following
    RemoteRenderBackend backend; // last: gone before what its signals fill

    Follower() {
        QObject::connect(&backend, &RenderBackend::frameReady,
                         [this](const BackendFrame& f) { frames.append(f); });
        QObject::connect(&backend, &RemoteRenderBackend::followStateChanged, [this](FollowState s) {
            firstState = firstState == FollowState::NotFollowing ? s : firstState;
            if (s == FollowState::Following) {
                followingFrom = frames.size();
            }
        });
        QObject::connect(&backend, &RemoteRenderBackend::lookAroundStarted,
                         [this](const Camera& c) { lookedFrom = c; });
    }
    bool waitState(FollowState state, int ms = 30000) {
        return QTest::qWaitFor([&] { return backend.followState() == state; }, ms);
    }
    bool waitFailed(int ms = 30000) {
        return QTest::qWaitFor([&] { return backend.status() == BackendStatus::Failed; }, ms);
    }
    // Waits for a frame equal to `expected` (>= 50 dB); the dB of the last one.
    double waitFrameLike(const ImageRGBA8& expected, int ms = 60000) {
        (void)QTest::qWaitFor(
            [&] { return !frames.isEmpty() && db(frames.back().image, expected) >= 50.0; }, ms);
        return frames.isEmpty() ? -1.0 : db(frames.back().image, expected);
    }
};

// The presenter's lecture as the followers meet it.
struct Lecture {
    explicit Lecture(const ServerProcess& s) : server(s) {}
    const ServerProcess& server;
    std::shared_ptr<const Volume> volume;
    QString session;
    QJsonObject invite;                  // invite-created: the code and its join link
    std::optional<SessionFollow> byLink; // the link read as the dialog reads it
    ImageRGBA8 teacher;                  // the presenter's newest frame
    glm::dvec3 tip{};                    // the arrow's anchor on the skull
    Camera turned;                       // the presenter's camera after the turn
};

QJsonObject arrow(double x0, double y0, double x1, double y1) {
    return {{"type", "mark"},
            {"kind", "arrow"},
            {"points", QJsonArray{QJsonArray{x0, y0}, QJsonArray{x1, y1}}}};
}

} // namespace

class TestWorkstationFollows : public QObject {
    Q_OBJECT

    // The mark's tip at its anchor's projection (2 px from ViewFrame's for `camera`)
    // in the mark's colour; the pointer's dot where it was sent.
    static void verifyOverlay(const BackendFrame& frame, const TeachingMarks& marks,
                              const Volume& volume, const Camera& camera, const glm::dvec3& tip,
                              const QString& when) {
        QVERIFY2(frame.projection, qPrintable(when + ": the frame has no projection"));
        const auto at = projectToImage(*frame.projection, tip);
        const auto expected = projectToImage(
            imageProjection(makeViewFrame(volume.geometry(), camera, kSide, kSide)), tip);
        QVERIFY(at && expected);
        const double off = glm::length(*at - *expected) * kSide;
        QVERIFY2(off < 2.0, qPrintable(QString("%1: the tip is %2 pixels off").arg(when).arg(off)));
        const QImage image = painted(frame, marks);
        const QColor tipColour = image.pixelColor(int(at->x * kSide), int(at->y * kSide));
        const QColor dot = image.pixelColor(int(0.3 * kSide), int(0.62 * kSide));
        if (!near(tipColour, kMarkColour) || !near(dot, kPointerColour)) {
            image.save(QDir::temp().filePath("workstation_follows_overlay.png"));
        }
        QVERIFY2(near(tipColour, kMarkColour),
                 qPrintable(QString("%1: %2 at the tip").arg(when, tipColour.name())));
        QVERIFY2(near(dot, kPointerColour),
                 qPrintable(QString("%1: %2 at the pointer").arg(when, dot.name())));
    }

    // The presenter: a session showing the head at kSide with ct-bone, an invite.
    static void openLecture(Lecture& lecture, RemoteTestClient& presenter) {
        QVERIFY(presenter.waitConnected() && presenter.authenticate());
        presenter.send({{"type", "session-create"}});
        lecture.session = presenter.waitForText("session-created")["session"].toString();
        QVERIFY(!lecture.session.isEmpty());
        QVERIFY(!openOnlySeries(presenter, kSide).isEmpty());
        QVERIFY(presenter.waitForCurrentFrame());
        presenter.send({{"type", "invite-create"}});
        lecture.invite = presenter.waitForText("invite-created");
        const QString link = lecture.invite["link"].toString();
        QVERIFY2(link.contains("#invite="), qPrintable(link));
        QString why;
        lecture.byLink = SessionFollow::fromLink(link, &why);
        QVERIFY2(lecture.byLink, qPrintable(why));
        QCOMPARE(lecture.byLink->url.port(), int(lecture.server.port()));
    }

    // The workstation follows by the link ("Follow a Session..."): the presenter's frame.
    static void followByTheLink(Lecture& lecture, RemoteTestClient& presenter, Follower& student,
                                FollowSessionDialog& dialog) {
        QObject::connect(&dialog, &FollowSessionDialog::followRequested,
                         [&](const SessionFollow& f) { student.backend.followSession(f); });
        dialog.show();
        dialog.linkEdit()->setText(lecture.invite["link"].toString());
        QTest::mouseClick(dialog.followButton(), Qt::LeftButton);
        QVERIFY2(student.waitState(FollowState::Following),
                 qPrintable(student.backend.statusMessage()));
        QCOMPARE(student.firstState, FollowState::Joining);
        QCOMPARE(student.backend.status(), BackendStatus::Connected);
        QVERIFY(student.backend.statusMessage().startsWith("following a session"));
        lecture.teacher = presenter.frames.back().decoded();
        const double got = student.waitFrameLike(lecture.teacher);
        QVERIFY2(got >= 50.0,
                 qPrintable(verdict(
                     got, student.frames.isEmpty() ? ImageRGBA8{} : student.frames.back().image,
                     "workstation_follows_join")));
        QVERIFY(student.frames.back().current);
    }

    // The presenter marks the skull and points, then turns 90 degrees: the new
    // frame, the mark still on its anchor.
    static void marksStayOnTheirAnchors(Lecture& lecture, RemoteTestClient& presenter,
                                        Follower& student) {
        presenter.send(arrow(0.5, 0.4, 0.7, 0.25));
        presenter.send({{"type", "pointer"}, {"x", 0.3}, {"y", 0.62}});
        QVERIFY(QTest::qWaitFor(
            [&] {
                return student.backend.teachingMarks().marks().size() == 1 &&
                       student.backend.teachingMarks().pointer().has_value();
            },
            30000));
        const Volume& volume = *lecture.volume;
        lecture.tip = student.backend.teachingMarks().marks().begin()->second.anchors[0];
        QVERIFY2(maxValueNear(volume, lecture.tip, 2.0) > 300.0, "the arrow's tip is not on bone");
        verifyOverlay(student.frames.back(), student.backend.teachingMarks(), volume, Camera{},
                      lecture.tip, "azimuth 0");
        QVERIFY(!QTest::currentTestFailed());

        presenter.change({{"type", "camera"}, {"azimuth", 90}});
        QVERIFY(presenter.waitForCurrentFrame());
        lecture.teacher = presenter.frames.back().decoded();
        const double got = student.waitFrameLike(lecture.teacher);
        QVERIFY2(got >= 50.0, qPrintable(verdict(got, student.frames.back().image,
                                                 "workstation_follows_turned")));
        lecture.turned.azimuth = 90.0;
        verifyOverlay(student.frames.back(), student.backend.teachingMarks(), volume,
                      lecture.turned, lecture.tip, "azimuth 90");
    }

    // Look around: from the session's camera, then the workstation's own view.
    // Back to teacher: the next frame is the presenter's newest.
    static void lookAroundThenBack(const Lecture& lecture, Follower& student,
                                   FollowSessionDialog& dialog) {
        QVERIFY(dialog.lookAroundButton()->isEnabled() && !dialog.backButton()->isEnabled());
        QTest::mouseClick(dialog.lookAroundButton(), Qt::LeftButton);
        QVERIFY2(student.waitState(FollowState::LookingAround),
                 qPrintable(student.backend.statusMessage()));
        QVERIFY(student.lookedFrom);
        QCOMPARE(student.lookedFrom->azimuth, 90.0);
        RenderDescription own;
        own.width = own.height = kSide;
        own.camera = *student.lookedFrom;
        own.camera.azimuth = -60.0;
        student.backend.request(own, {});
        QVERIFY(QTest::qWaitFor(
            [&] {
                const BackendFrame& f = student.frames.back();
                return f.current && !f.interactive && f.image.width == kSide &&
                       db(f.image, lecture.teacher) < 30.0;
            },
            60000));
        verifyOverlay(student.frames.back(), student.backend.teachingMarks(), *lecture.volume,
                      own.camera, lecture.tip, "looking around");
        QVERIFY(!QTest::currentTestFailed());

        QVERIFY(dialog.backButton()->isEnabled());
        QTest::mouseClick(dialog.backButton(), Qt::LeftButton);
        QVERIFY(student.waitState(FollowState::Following));
        const qsizetype looked = student.followingFrom;
        QVERIFY(QTest::qWaitFor([&] { return student.frames.size() > looked; }, 30000));
        const double got = db(student.frames[looked].image, lecture.teacher);
        qInfo("back to teacher: %.1f dB against the presenter's frame", got);
        QVERIFY2(got >= 50.0, qPrintable(verdict(got, student.frames[looked].image,
                                                 "workstation_follows_back")));
    }

    // The 3D view follows too, with no volume loaded: the teacher's frame with the
    // mark on it; a drag looks around, from the teacher's camera.
    static void theViewFollowsWithNoVolume(const Lecture& lecture, VolumeView& view) {
        view.resize(kSide, kSide);
        view.show();
        QVERIFY(QTest::qWaitForWindowExposed(&view));
        view.followSession(*lecture.byLink);
        QVERIFY2(QTest::qWaitFor(
                     [&] {
                         return view.followsSession() && !view.lastFrame().pixels.empty() &&
                                db(view.lastFrame(), lecture.teacher) >= 50.0;
                     },
                     60000),
                 qPrintable(view.notice()));
        QVERIFY(QTest::qWaitFor(
            [&] { return view.remoteBackend().teachingMarks().marks().size() == 1; }, 20000));
        const auto tipInView =
            projectToImage(imageProjection(makeViewFrame(lecture.volume->geometry(), lecture.turned,
                                                         kSide, kSide)),
                           lecture.tip);
        QVERIFY(tipInView);
        // Within 2 pixels: the view's notice line is drawn over the frame too.
        const QImage shown = view.grabImage();
        bool marked = false;
        for (int dy = -2; dy <= 2; ++dy) {
            for (int dx = -2; dx <= 2; ++dx) {
                marked = marked || near(shown.pixelColor(int(tipInView->x * kSide) + dx,
                                                         int(tipInView->y * kSide) + dy),
                                        kMarkColour);
            }
        }
        if (!marked) {
            shown.save(QDir::temp().filePath("workstation_follows_view.png"));
        }
        QVERIFY2(marked, "the view does not draw the mark at its anchor");
        QTest::mousePress(&view, Qt::LeftButton, {}, QPoint(64, 64));
        QVERIFY(QTest::qWaitFor(
            [&] { return view.remoteBackend().followState() == FollowState::LookingAround; },
            20000));
        QTest::mouseMove(&view, QPoint(84, 64));
        QTest::mouseMove(&view, QPoint(104, 64));
        QTest::mouseRelease(&view, Qt::LeftButton, {}, QPoint(104, 64));
        QCOMPARE(view.camera().azimuth, 90.0 + 40 * VolumeView::kDegreesPerPixel);
        QVERIFY(QTest::qWaitFor(
            [&] {
                return view.lastFrameCurrent() && !view.lastFrame().pixels.empty() &&
                       db(view.lastFrame(), lecture.teacher) < 30.0;
            },
            60000));
    }

    // A colleague with a token follows by the session's id; a wrong id is refused.
    // The invite revoked: the student is dropped, saying why; the link lets no one
    // in. The session ends (its token holders leave): a follower by invite is told so.
    static void othersFollowUntilTheEnd(const Lecture& lecture, RemoteTestClient& presenter,
                                        Follower& student, const FollowSessionDialog& dialog) {
        const ServerProcess& server = lecture.server;
        Follower colleague;
        colleague.backend.followSession({server.url(), {}, kToken, "no-such-session"});
        QVERIFY(colleague.waitFailed());
        QVERIFY2(colleague.backend.statusMessage().contains("no session no-such-session"),
                 qPrintable(colleague.backend.statusMessage()));
        colleague.backend.followSession({server.url(), {}, kToken, lecture.session});
        QVERIFY2(colleague.waitState(FollowState::Following),
                 qPrintable(colleague.backend.statusMessage()));
        const double got = colleague.waitFrameLike(lecture.teacher);
        QVERIFY2(got >= 50.0, qPrintable(QString("by token: %1 dB").arg(got)));

        presenter.send({{"type", "invite-revoke"}, {"invite", lecture.invite["invite"]}});
        QVERIFY(student.waitFailed());
        QVERIFY2(student.backend.statusMessage().contains("the invite was revoked"),
                 qPrintable(student.backend.statusMessage()));
        QCOMPARE(student.backend.followState(), FollowState::NotFollowing);
        QVERIFY2(dialog.statusLabel()->text().contains("the invite was revoked"),
                 qPrintable(dialog.statusLabel()->text()));
        Follower late;
        late.backend.followSession(*lecture.byLink);
        QVERIFY(late.waitFailed());
        QVERIFY2(late.backend.statusMessage().contains("refused the invite") &&
                     late.backend.statusMessage().contains("the invite was revoked"),
                 qPrintable(late.backend.statusMessage()));
        QVERIFY(late.frames.isEmpty());

        const qsizetype before = presenter.texts.size();
        presenter.send({{"type", "invite-create"}});
        const QString second =
            presenter.waitForText("invite-created", 20000, before)["link"].toString();
        QString why;
        const auto again = SessionFollow::fromLink(second, &why);
        QVERIFY2(again, qPrintable(why));
        Follower last;
        last.backend.followSession(*again);
        QVERIFY2(last.waitState(FollowState::Following), qPrintable(last.backend.statusMessage()));
        colleague.backend.disconnectFromServer();
        presenter.send({{"type", "session-leave"}});
        QVERIFY(last.waitFailed());
        QVERIFY2(last.backend.statusMessage().contains("has ended"),
                 qPrintable(last.backend.statusMessage()));
    }

private slots:
    void joinLinksAreReadOrRefused() {
        QString why;
        auto follow =
            SessionFollow::fromLink("https://lecture.example.org:8443/#invite=q0Xb-_9z", &why);
        QVERIFY2(follow, qPrintable(why));
        QCOMPARE(follow->url, QUrl("wss://lecture.example.org:8443/"));
        QCOMPARE(follow->invite, QString("q0Xb-_9z"));
        follow = SessionFollow::fromLink(" http://127.0.0.1:9000/#invite=abc ", &why);
        QVERIFY2(follow, qPrintable(why));
        QCOMPARE(follow->url, QUrl("ws://127.0.0.1:9000/"));
        const std::pair<const char*, const char*> refused[] = {
            {"", "join link: empty"},
            {"ftp://host/#invite=abc", "must start with https://"},
            {"lecture-host:8443", "must start with https://"},
            {"https:///#invite=abc", "no host"},
            {"https://host:8443/", "no invite"},
            {"https://host:8443/#invite=", "is empty"},
            {"https://host:8443/#invite=a%20b", "invite: not an invite code"},
        };
        for (const auto& [link, reason] : refused) {
            why.clear();
            QVERIFY2(!SessionFollow::fromLink(link, &why), link);
            QVERIFY2(why.contains(reason), qPrintable(QString::fromUtf8(link) + ": " + why));
        }
        // Without an invite: a token and a session are needed, and the backend says so.
        RemoteRenderBackend backend;
        backend.followSession({QUrl("ws://127.0.0.1:1/"), {}, {}, "abc"});
        QCOMPARE(backend.status(), BackendStatus::Failed);
        QVERIFY2(backend.statusMessage().startsWith("token:"), qPrintable(backend.statusMessage()));
        backend.followSession({QUrl("ws://127.0.0.1:1/"), {}, "t", {}});
        QVERIFY2(backend.statusMessage().startsWith("session:"),
                 qPrintable(backend.statusMessage()));
        QCOMPARE(backend.followState(), FollowState::NotFollowing);

        // The dialog says what is wrong with a link, and asks for nothing.
        FollowSessionDialog dialog(backend);
        dialog.show();
        int asked = 0;
        QObject::connect(&dialog, &FollowSessionDialog::followRequested, [&] { ++asked; });
        dialog.linkEdit()->setText("https://host:8443/");
        QTest::mouseClick(dialog.followButton(), Qt::LeftButton);
        QVERIFY2(dialog.statusLabel()->text().contains("Cannot follow: join link: no invite"),
                 qPrintable(dialog.statusLabel()->text()));
        QCOMPARE(asked, 0);
        QVERIFY(!dialog.lookAroundButton()->isEnabled() && !dialog.backButton()->isEnabled());
    }

    void theWorkstationFollowsAPresentersSession() {
        if (!std::filesystem::exists(kDemoHead.toStdString())) {
            QSKIP(kDemoHeadMissing);
        }
        ServerProcess server("cpu", kDemoHead);
        QVERIFY2(server.started(), qPrintable(server.startError()));
        Lecture lecture{server};
        lecture.volume = std::make_shared<const Volume>(readInVesalius(kDemoHead.toStdString()));
        RemoteTestClient presenter(server.port(), kV4);
        openLecture(lecture, presenter);
        if (QTest::currentTestFailed()) {
            return;
        }
        Follower student;
        FollowSessionDialog dialog(student.backend);
        followByTheLink(lecture, presenter, student, dialog);
        if (QTest::currentTestFailed()) {
            return;
        }
        marksStayOnTheirAnchors(lecture, presenter, student);
        if (QTest::currentTestFailed()) {
            return;
        }
        lookAroundThenBack(lecture, student, dialog);
        if (QTest::currentTestFailed()) {
            return;
        }
        // Kept to the end: one more follower by the invite when it is revoked.
        VolumeView view(nullptr, VolumeView::Backend::Cpu);
        theViewFollowsWithNoVolume(lecture, view);
        if (QTest::currentTestFailed()) {
            return;
        }
        othersFollowUntilTheEnd(lecture, presenter, student, dialog);
    }
};

int main(int argc, char** argv) {
    useOffscreenPlatform();
    QApplication app(argc, argv);
    TestWorkstationFollows test;
    return QTest::qExec(&test, argc, argv);
}

#include "test_workstation_follows.moc"
