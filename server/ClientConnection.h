#pragma once
// One WebSocket client of the render server: authentication (the auth
// message, or a token or an invite offered as a WebSocket subprotocol), the view it
// watches (its own, or a teaching session's), and the frames it is sent.
// The client is only ever sent the newest frame: one that arrives while the
// previous one is still being written replaces any frame waiting behind it.

#include <QByteArray>
#include <QElapsedTimer>
#include <QObject>
#include <QPointer>
#include <QTimer>
#include <QWebSocket>

#include <cstdint>
#include <map>
#include <memory>
#include <string>

#include "protocol/ProtocolMessages.h"

namespace lucent::remote {

class RecordingReplay;
class RenderServer;
class SessionRecorder;
class TeachingSession;
class ViewStream;

// Camera updates: a burst of this many, then this many per second.
inline constexpr double kCameraBurst = 60.0;
inline constexpr double kCameraPerSecond = 60.0;
// Qt closes a connection (code 1009) whose incoming frame or message is larger
// than this, before buffering it; messages between kMaxMessageBytes and this
// get the protocol's "too-large" error first, and then the same close code.
inline constexpr qint64 kMaxIncomingWebSocketBytes = 4 * qint64(kMaxMessageBytes);
// A client must authenticate within this time.
inline constexpr int kAuthTimeoutMs = 10000;
// The prefix of the subprotocol that carries a client's token (browsers cannot
// set headers on a WebSocket); the version rides in another (ProtocolVersion.h).
inline constexpr char kTokenSubprotocolPrefix[] = "lucent.token.";
// The prefix of the subprotocol that carries an invite code (version 3).
inline constexpr char kInviteSubprotocolPrefix[] = "lucent.invite.";

class ClientConnection : public QObject {
    Q_OBJECT
public:
    // Takes the socket (as a Qt child).
    ClientConnection(quint64 id, QWebSocket* socket, RenderServer& server);
    ~ClientConnection() override;
    // Authenticates at once when the handshake offered a token subprotocol.
    void start();

    quint64 id() const { return id_; }
    // The protocol version of this connection: the lucent.v<N> subprotocol the
    // handshake selected, 1 when none.
    int version() const { return version_; }
    // The number of the invite it came with; 0 when it came with a token (an
    // invite's holder may only follow its session).
    std::uint64_t invite() const { return invite_; }
    void sendJson(const std::string& json);
    // Sends an error; a fatal one closes the connection after it.
    void sendError(const std::string& code, const std::string& message, bool fatal);
    // A finished frame of the view it watches: sent now, or kept (replacing
    // any older one of its channel: 0 the 3D view, sliceChannel() a slice view)
    // until the socket has written what it holds.
    void offerFrame(const QByteArray& message, int channel = 0);
    // Nothing unsent: the next render may start for a view it paces.
    bool readyForFrame() const;
    // Leaves its teaching session, if any (on a close too).
    void leaveSession();
    // Its session ended under it: session-left, and a follower by invite,
    // which can do nothing else, is closed.
    void sessionEnded(const std::string& sessionId);

signals:
    void closed(quint64 id);

private:
    void onText(const QString& text);
    void onBinary(const QByteArray& data);
    void onBytesWritten();
    void onKeepalive();
    void authenticate(const std::string& token);
    void handle(const ClientMessage& message);
    // Teaching sessions (ClientSessions.cpp): session-create, -join, -handover, -leave.
    void handleSession(const ClientMessage& message);
    void joinSession(TeachingSession& session);
    // Invites (ClientInvites.cpp): auth by invite, invite-create and invite-revoke,
    // and what an invite's holder may not do.
    void authenticateInvite(const std::string& code);
    void handleInvite(const ClientMessage& message);
    bool refusedToInvitee(const ClientMessage& message);
    // Free look (ClientFreeLook.cpp): free-look and free-look-recall; a view
    // message of this client, sent to the view it controls (null: none).
    void handleFreeLook(const ClientMessage& message);
    ViewStream* controlledView(const ClientMessage& viewMessage);
    std::string linkOrigin() const;
    // Recording and replay (ClientRecordings.cpp): record, recording-list,
    // replay, replay-step, replay-stop; what this client's view accepted, kept
    // by its recording; both end when the view changes hands or series.
    void handleRecording(const ClientMessage& message);
    void startRecording();
    void startReplay(const ReplayRequest& request);
    void beginReplay(const ReplayRequest& request, Recording recording);
    void recordAccepted(const ClientMessage& message);
    void stopRecording(const std::string& reason);
    void stopReplay(const std::string& reason);
    void viewChanging();
    void closeNormally(const QString& reason);
    // pointer, mark and marks-clear (ClientMarks.cpp); false for other messages.
    bool handleMark(const ClientMessage& message);
    // list and open (ClientSeries.cpp).
    void handleOpen(const OpenRequest& open);
    void sendList();
    bool takeCameraToken();

    quint64 id_;
    int version_;
    QPointer<QWebSocket> socket_;
    RenderServer& server_;
    QTimer authTimer_;
    QTimer keepaliveTimer_;
    QElapsedTimer lastHeard_; // since the last message or pong
    bool authenticated_ = false;
    std::uint64_t invite_ = 0;
    bool closing_ = false;

    ViewStream* ownView_;                       // child: the view when in no session
    QPointer<TeachingSession> session_;         // when in one
    std::map<int, QByteArray> pendingFrames_;   // by channel
    std::unique_ptr<SessionRecorder> recorder_; // while this client records
    std::unique_ptr<RecordingReplay> replay_;   // while it replays

    double cameraTokens_ = kCameraBurst;
    QElapsedTimer cameraClock_;
    double pointerTokens_ = kCameraBurst; // the pointer is limited as the camera is
    QElapsedTimer pointerClock_;
};

} // namespace lucent::remote
