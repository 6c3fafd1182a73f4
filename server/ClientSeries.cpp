// ClientConnection: the series a client may open (list) and opening one (open),
// into its own view or its teaching session's.
#include "server/ClientConnection.h"
#include "server/ClientConnection_p.h"
#include "server/RenderServer.h"
#include "server/TeachingSession.h"
#include "server/ViewStream.h"

namespace lucent::remote {
namespace {

SeriesSummary seriesSummary(const SeriesEntry& s, bool withDescription) {
    return {s.id, withDescription ? s.description : std::string(), s.modality, s.geometry.dims};
}

} // namespace

void ClientConnection::sendList() {
    SeriesListReply list;
    if (session_ && !session_->isPresenter(*this)) {
        // A follower sees the session's de-identified series only.
        if (const auto& shared = session_->view().series()) {
            list.series.push_back(seriesSummary(*shared, false));
        }
    } else {
        for (const auto& s : server_.series()) {
            list.series.push_back(seriesSummary(*s, true));
        }
    }
    sendJson(writeServerMessage(list));
}

void ClientConnection::handleOpen(const OpenRequest& open) {
    auto series = server_.findSeries(open.series);
    if (!series) {
        sendError("not-found", "no series with uid '" + open.series.substr(0, 128) + "'", false);
        return;
    }
    qCInfo(lcClient) << "client" << id_ << "opened a series";
    viewChanging();
    if (session_) {
        session_->share(std::move(series)); // every member gets `opened` when it is ready
    } else {
        sendJson(ownView_->open(std::move(series)));
    }
}

} // namespace lucent::remote
