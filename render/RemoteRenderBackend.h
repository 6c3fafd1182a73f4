#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <QElapsedTimer>
#include <QSet>
#include <QTimer>

#include "protocol/ServerMessages.h"
#include "render/RemoteServerSettings.h"
#include "render/RenderBackend.h"
#include "render/SessionFollow.h"
#include "render/TeachingMarks.h"

class QWebSocket;

namespace lucent {

// A series a server offers (its `series` reply).
struct OfferedSeries {
    QString uid; // what `open` takes
    QString description;
    QString modality;
    glm::ivec3 dims{0};
};

// Where a follower of a teaching session is (RemoteRenderBackend::followSession).
enum class FollowState {
    NotFollowing,
    Joining,       // connecting, authenticating, waiting for the session's series
    Following,     // the session's frames: the presenter's view
    LookingAround, // free look: its own view of the session's series
};

// A lucent-server client (docs/protocol.md, version 2, and version 1 servers)
// behind RenderBackend: authenticates, lists the server's series and opens the
// one matching the loaded volume (or the one the settings name), sends only the
// view messages that changed (remote::viewMessages: size, transfer function,
// mode, clip box, camera, sampling; a drag as interaction start/end, so the
// server adapts its JPEG frames to hold the frame rate), decodes the PNG
// (still) and JPEG (interactive) frames, tells from their `seq` whether they
// show the newest request. A lost connection is reopened by itself with
// growing delays and the whole view sent again; the status says connecting,
// connected, reconnecting or failed (with the server's refusal: a wrong token,
// a series it does not have).
//
// All JSON goes through the protocol's one writer and reader (protocol/). A
// version 1 server has no sampling message: sampling other than its default is
// not sent but refused with frameFailed (naming the settings), and the frames
// that follow are never current.
class RemoteRenderBackend : public RenderBackend {
    Q_OBJECT

public:
    // Camera messages at most this often (the server drops more than 60 a second).
    static constexpr int kCameraIntervalMs = 20;
    // A connection attempt that has not opened after this long is given up (and retried).
    static constexpr int kHandshakeTimeoutMs = 10000;

    explicit RemoteRenderBackend(QObject* parent = nullptr);
    ~RemoteRenderBackend() override;

    // Connects (again) with these settings; the view requested so far is sent
    // once the series is open. Bad settings fail at once, naming the field.
    void connectTo(const RemoteServerSettings& settings);
    void disconnectFromServer();
    const RemoteServerSettings& settings() const { return settings_; }

    void setVolume(std::shared_ptr<const Volume> volume) override;
    void request(const RenderDescription& still, const FrameOptions& options) override;
    BackendStatus status() const override { return status_; }
    QString statusMessage() const { return statusMessage_; }

    // From the server's hello: what it renders with ("cpu", "gl: ...").
    QString serverBackend() const { return serverBackend_; }
    // The id of the series open on the server; empty before.
    QString openSeries() const { return openSeries_; }
    // What the server offered in its last `series` reply (kept after a failure,
    // so that the user can pick one).
    const std::vector<OfferedSeries>& offeredSeries() const { return offered_; }
    // The protocol version of the connection, from the server's hello (0 before).
    int serverVersion() const { return serverVersion_; }
    // View messages the server has accepted or owes a frame for on this connection.
    std::uint64_t sentSeq() const { return seqSent_; }

    // The first retry after firstMs, each next one twice as late, at most maxMs.
    void setReconnectDelays(int firstMs, int maxMs);
    // false: a connection that fails or is lost is not tried again; the status
    // becomes Failed, saying why (for one-shot clients such as lucent-cli).
    void setRetrying(bool retrying) { retrying_ = retrying; }
    // The newest protocol version this client offers (remote::kProtocolVersion):
    // an older one gets it served as a server of that version serves it.
    void setProtocolVersion(int version) { offeredVersion_ = version; }

    // Teaching (RemoteRenderSession.cpp): while presenting, each connection
    // starts a teaching session before it opens the series, so that the view is
    // the session's and followers watch its de-identified copy. Changing it
    // connects again; a new connection is a new session (the last one's invites
    // end with it).
    void setPresenting(bool presenting);
    bool presenting() const { return presenting_; }
    // The session this client presents; empty when none.
    QString sessionId() const { return sessionId_; }
    // Invites to it (protocol version 3; the answers come as signals): a
    // lifetime in seconds, or none (until the session ends, at most a day).
    void createInvite(std::optional<std::int64_t> lifetimeSeconds);
    void revokeInvite(std::uint64_t invite);
    // The session's pointer and marks (version 4), as the server sent them (its
    // own too: the server sends them to every member). The presenter points (at
    // fractions of the view; none hides the pointer), marks and clears.
    const TeachingMarks& teachingMarks() const { return marks_; }
    void point(std::optional<glm::dvec2> at);
    void placeMark(const remote::MarkPlace& mark);
    void clearMarks();
    // Free look (protocol version 4): every follower looking on its own goes
    // back to the session's view (freeLookChanged says how many look).
    void recallFreeLook();

    // Following (RemoteRenderFollow.cpp): joins a running session (by invite or
    // by token and session id) and shows its frames, its pointer and marks.
    // Nothing of the view goes to the server, except while looking around (free
    // look, version 4): then the camera and size of request() do, and the
    // frames are this client's own. connectTo() or disconnectFromServer() stop
    // following. Bad settings, a refused invite and the session's end: status
    // Failed, saying why.
    void followSession(const SessionFollow& follow);
    const std::optional<SessionFollow>& followed() const { return follow_; }
    FollowState followState() const { return followState_; }
    void lookAround();
    void backToTeacher();

signals:
    void marksChanged();
    void sessionChanged(const QString& id);
    void inviteCreated(const lucent::remote::InviteCreated& invite);
    void inviteRevoked(quint64 invite);
    // Why an invite could not be made or revoked.
    void inviteRefused(const QString& why);
    // How many followers of the session look on their own, of at most `limit`.
    void freeLookChanged(int looking, int limit);
    void followStateChanged(lucent::FollowState state);
    // Free look began from the session's camera (a view adopts it, then turns).
    void lookAroundStarted(const lucent::Camera& camera);

private:
    enum class Phase { Idle, Connecting, Authenticating, Listing, Opening, Open };
    struct WantedView {
        RenderDescription still;
        bool interactive = false;
    };

    void open();
    void onConnected();
    void onText(const QString& text);
    void onBinary(const QByteArray& message);
    void onLost(const QString& why);
    void onServerError(const QString& code, const QString& message, bool fatal);
    // session-created, invite-created, invite-revoked; false for other messages.
    bool onSessionMessage(const remote::ServerMessage& message);
    // A refusal of invite-create or invite-revoke (reported by inviteRefused).
    bool isInviteRefusal(const QString& code, const QString& message) const;
    void setSessionId(const QString& id);
    // hello, opened, session-left, free-look-started and -ended of a follower;
    // false for other messages.
    bool onFollowMessage(const remote::ServerMessage& message);
    // A refusal of free-look or session-join (reported by frameFailed or fail).
    bool onFollowError(const QString& code, const QString& message);
    void setFollowState(FollowState state);
    // The view (RemoteRenderView.cpp, with onBinary's frames): the series
    // chosen and opened, the view messages that changed.
    void chooseSeries();
    void sync();
    void send(const std::string& json);
    // A view message of this type, as JSON: counted, and its kind no longer refused.
    void sendView(const std::string& type, const std::string& json);
    // A view message that the server's version does not have.
    void refuseNewerMessage(const std::string& type, const std::string& json,
                            const RenderDescription& wanted);
    // Stops the timers and drops the socket (no status change).
    void closeConnection();
    void fail(const QString& message);
    void setStatus(BackendStatus status, const QString& message);
    QString where() const;

    // Disconnects its signals and deletes it later: a socket may be dropped
    // from inside one of its own signals.
    struct SocketDropper {
        void operator()(QWebSocket* socket) const;
    };

    RemoteServerSettings settings_;
    std::unique_ptr<QWebSocket, SocketDropper> socket_;
    Phase phase_ = Phase::Idle;
    BackendStatus status_ = BackendStatus::Disconnected;
    QString statusMessage_;
    QString serverBackend_;
    QString openSeries_;
    std::vector<OfferedSeries> offered_;
    QString refusal_; // a fatal refusal, reported when the server closes
    bool retryAfterRefusal_ = true;
    bool retrying_ = true;
    bool presenting_ = false;
    QString sessionId_;
    bool wasOpen_ = false; // this connection got as far as an open series
    int serverVersion_ = 0;
    int offeredVersion_; // set in the constructor

    std::optional<SessionFollow> follow_;
    FollowState followState_ = FollowState::NotFollowing;

    TeachingMarks marks_;
    std::shared_ptr<const Volume> volume_;
    std::optional<WantedView> wanted_;
    // What the server has been told since `open`: the last view message of each
    // type, as written (a message equal to it is not sent again).
    std::map<std::string, std::string> sent_;
    bool interacting_ = false;   // an interaction start was sent and no end yet
    bool sentOffCentre_ = false; // a camera with distance or pan went to a version 1 server
    std::uint64_t seqSent_ = 0;
    std::uint64_t firstViewSeq_ = 0; // frames before this show the server's defaults
    // Kinds of view message the server refused ("camera", ...; "" when it did
    // not say), each until a new value of that kind is sent.
    QSet<QString> refused_;

    QTimer reconnectTimer_;
    QTimer handshakeTimer_;
    QTimer cameraTimer_;
    QElapsedTimer cameraClock_;
    int firstDelayMs_ = 500;
    int maxDelayMs_ = 8000;
    int nextDelayMs_ = 500;
};

} // namespace lucent
