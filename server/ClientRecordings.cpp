// ClientConnection: recording and replay (docs/protocol.md, "Recording and
// replay"). A presenter (a token's holder who controls its view: its own, or
// its session's) records what its view accepts into the store and replays any
// recording of the store into its view; in a session the followers watch it
// from the de-identified copy. Followers by invite may do neither (forbidden,
// refusedToInvitee); followers by token may list.
#include <QFuture>
#include <QLoggingCategory>
#include <QPromise>
#include <QThreadPool>
#include <QTimer>

#include <memory>

#include "server/ClientConnection.h"
#include "server/RecordingReplay.h"
#include "server/RecordingStore.h"
#include "server/RenderServer.h"
#include "server/SessionRecorder.h"
#include "server/TeachingSession.h"
#include "server/ViewMarks.h"
#include "server/ViewStream.h"

namespace lucent::remote {
namespace {

Q_LOGGING_CATEGORY(lcRecording, "lucent.server.recording")

struct LoadedRecording {
    std::shared_ptr<Recording> recording; // null when it could not be read
    std::string error;
};

QFuture<LoadedRecording> readInBackground(std::filesystem::path file) {
    auto promise = std::make_shared<QPromise<LoadedRecording>>();
    QFuture<LoadedRecording> future = promise->future();
    QThreadPool::globalInstance()->start([promise, file = std::move(file)] {
        promise->start();
        LoadedRecording loaded;
        try {
            loaded.recording = std::make_shared<Recording>(readRecording(file));
        } catch (const RecordingError& e) {
            loaded.error = e.what();
        }
        promise->addResult(std::move(loaded));
        promise->finish();
    });
    return future;
}

} // namespace

void ClientConnection::handleRecording(const ClientMessage& message) {
    const std::string type(messageType(message));
    if (std::holds_alternative<RecordingListRequest>(message)) {
        const auto& store = server_.storeDir();
        sendJson(writeServerMessage(RecordingList{store.empty() ? std::vector<RecordingSummary>{}
                                                                : listRecordings(store)}));
        return;
    }
    if (session_ && !session_->isPresenter(*this)) {
        sendError("not-presenter", type + ": this client does not hold control of the session",
                  false);
        return;
    }
    if (const auto* record = std::get_if<RecordRequest>(&message)) {
        if (!record->start) {
            if (!recorder_) {
                sendError("bad-request", "record: this client is not recording", false);
                return;
            }
            stopRecording("stopped");
            return;
        }
        startRecording();
    } else if (const auto* replay = std::get_if<ReplayRequest>(&message)) {
        startReplay(*replay);
    } else if (!replay_) {
        sendError("bad-request", type + ": no replay is running", false);
    } else if (std::holds_alternative<ReplayStop>(message)) {
        stopReplay("stopped");
    } else if (replay_->pace() != ReplayPace::Step) {
        sendError("bad-request", "replay-step: the replay runs at the original pace", false);
    } else {
        replay_->step();
    }
}

void ClientConnection::startRecording() {
    if (recorder_) {
        sendError("bad-request", "record: already recording (" + recorder_->id() + ")", false);
        return;
    }
    if (replay_) {
        sendError("bad-request", "record: a replay is running (replay-stop first)", false);
        return;
    }
    ViewStream& view = session_ ? session_->view() : *ownView_;
    const auto& original = session_ ? session_->original() : ownView_->series();
    if (!view.accepting() || !original) {
        sendError("bad-request", "record: open a series first", false);
        return;
    }
    if (server_.storeDir().empty()) {
        sendError("bad-request", "record: this server has no store to keep recordings", false);
        return;
    }
    recorder_ = std::make_unique<SessionRecorder>(server_.storeDir(), original->id,
                                                  view.description(), &view);
    QTimer::singleShot(std::chrono::milliseconds(kMaxRecordingMs), recorder_.get(),
                       [this] { stopRecording("limit"); });
    qCInfo(lcRecording) << "client" << id_ << "records" << recorder_->id().c_str();
    sendJson(writeServerMessage(RecordingStarted{recorder_->id()}));
}

void ClientConnection::recordAccepted(const ClientMessage& message) {
    if (!recorder_) {
        return;
    }
    const ViewStream& view = session_ ? session_->view() : *ownView_;
    if (recorder_->view() != &view) {
        stopRecording("view");
    } else if (!recorder_->add(message)) {
        stopRecording("limit");
    }
}

void ClientConnection::stopRecording(const std::string& reason) {
    if (!recorder_) {
        return;
    }
    const std::unique_ptr<SessionRecorder> recorder = std::move(recorder_);
    try {
        const RecordingStopped stopped = recorder->finish(reason);
        qCInfo(lcRecording) << "client" << id_ << "stored recording" << stopped.recording.c_str()
                            << stopped.views << "views" << stopped.durationMs << "ms";
        sendJson(writeServerMessage(stopped));
    } catch (const std::exception& e) {
        qCWarning(lcRecording) << "recording" << recorder->id().c_str() << "not stored";
        sendError("render-failed", std::string("record: the recording was lost: ") + e.what(),
                  false);
    }
}

void ClientConnection::startReplay(const ReplayRequest& request) {
    if (recorder_) {
        sendError("bad-request", "replay: this client is recording (record stop first)", false);
        return;
    }
    const std::filesystem::path file = recordingFile(server_.storeDir(), request.recording);
    std::error_code missing;
    if (server_.storeDir().empty() || !std::filesystem::is_regular_file(file, missing)) {
        sendError("not-found", "replay: no recording '" + request.recording + "'", false);
        return;
    }
    // Off the event loop: the largest recording takes seconds to read, and the
    // server's other views go on meanwhile.
    readInBackground(file).then(this, [this, request](const LoadedRecording& loaded) {
        if (!loaded.recording) {
            // The store's own path only: the recording's id, never a patient's file.
            qCWarning(lcRecording) << "recording" << request.recording.c_str() << "unreadable";
            sendError("render-failed", "replay: " + loaded.error, false);
            return;
        }
        beginReplay(request, std::move(*loaded.recording));
    });
}

void ClientConnection::beginReplay(const ReplayRequest& request, Recording recording) {
    if (closing_ || recorder_ || (session_ && !session_->isPresenter(*this))) {
        return; // it started recording or handed over while the recording was read
    }
    auto series = server_.findSeries(recording.header.series);
    if (!series) {
        sendError("not-found",
                  "replay: recording '" + request.recording +
                      "' shows a series this server no longer has",
                  false);
        return;
    }
    stopReplay("stopped"); // a new replay replaces the one running
    // The recorded start view, applied before the series shows: its first frame.
    ViewStream& view = session_ ? session_->view() : *ownView_;
    if (session_) {
        session_->share(series);
    } else {
        view.reset(*series);
    }
    for (const ClientMessage& m : recording.start) {
        if (const auto error = view.apply(m)) {
            sendError("render-failed", "replay: the start view: " + *error, false);
        }
    }
    if (!session_) {
        sendJson(view.show(std::move(series)));
    }
    RecordingReplay::Hooks hooks;
    // Messages isRecordedMessage() keeps that are not view messages (pointer,
    // marks) go to the session's members here.
    hooks.apply = [this, view = QPointer<ViewStream>(&view)](const ClientMessage& m) {
        if (!view) {
            return;
        }
        if (isViewMessage(m)) {
            (void)view->apply(m); // a recording's messages were checked when it was read
            if (session_ && &session_->view() == view.data()) {
                session_->freeLook().follow(m); // followers looking on their own follow it too
            }
        } else if (const auto* pointer = std::get_if<PointerUpdate>(&m)) {
            view->marks().point(*pointer);
        } else if (const auto* mark = std::get_if<MarkPlace>(&m)) {
            // Anchored again on the view as it is now: as it was when it was placed.
            if (const auto refused = view->marks().place(*mark, *this)) {
                sendError(refused->first, "replay: " + refused->second, false);
            }
        } else if (std::holds_alternative<MarksClear>(m)) {
            view->marks().clear(true);
        }
    };
    hooks.tell = [this](const std::string& json) { sendJson(json); };
    hooks.ended = [this](const std::string& reason) { stopReplay(reason); };
    qCInfo(lcRecording) << "client" << id_ << "replays" << request.recording.c_str()
                        << replayPaceName(request.pace);
    replay_ = std::make_unique<RecordingReplay>(request.recording, std::move(recording),
                                                request.pace, view, std::move(hooks));
    replay_->begin(); // last: a replay with nothing to play ends in it
}

void ClientConnection::stopReplay(const std::string& reason) {
    if (!replay_) {
        return;
    }
    const ViewStream& view = session_ ? session_->view() : *ownView_;
    sendJson(writeServerMessage(ReplayEnded{
        replay_->id(), reason, CameraUpdate{optionUpdate(kWireCamera, view.description())}}));
    replay_->cancel();
    // Later: this may run inside the replay's own call.
    replay_.release()->deleteLater();
}

void ClientConnection::viewChanging() {
    stopRecording("view");
    stopReplay("view");
}

} // namespace lucent::remote
