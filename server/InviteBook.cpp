#include "server/InviteBook.h"

#include <QCryptographicHash>
#include <QDateTime>
#include <QRandomGenerator>

#include <algorithm>
#include <array>

#include "server/ConstantTime.h"

namespace lucent::remote {
namespace {

constexpr int kCodeBytes = 24; // 192 bits
constexpr std::int64_t kForgetAfterSeconds = 24 * 60 * 60;

std::string digestOf(std::string_view code) {
    return QCryptographicHash::hash(QByteArrayView(code.data(), qsizetype(code.size())),
                                    QCryptographicHash::Sha256)
        .toStdString();
}

std::int64_t now() {
    return QDateTime::currentSecsSinceEpoch();
}

} // namespace

std::optional<InviteBook::Issued> InviteBook::issue(const QString& session,
                                                    std::int64_t lifetimeSeconds) {
    forgetOld();
    const auto issued = std::count_if(records_.begin(), records_.end(),
                                      [&](const Record& r) { return r.session == session; });
    if (issued >= kMaxPerSession) {
        return std::nullopt;
    }
    std::array<quint32, kCodeBytes / 4> words{};
    QRandomGenerator::system()->fillRange(words.data(), qsizetype(words.size()));
    const QByteArray code =
        QByteArray(reinterpret_cast<const char*>(words.data()), kCodeBytes)
            .toBase64(QByteArray::Base64UrlEncoding | QByteArray::OmitTrailingEquals);
    Issued invite{nextNumber_++, code.toStdString(), now() + lifetimeSeconds};
    records_.push_back({digestOf(invite.code), session, invite.number, invite.expires});
    return invite;
}

InviteBook::Found InviteBook::find(std::string_view code) const {
    const std::string digest = digestOf(code);
    const Record* match = nullptr;
    for (const Record& r : records_) {
        if (equalInConstantTime(digest, r.digest)) {
            match = &r;
        }
    }
    if (!match) {
        return {};
    }
    const State state = match->sessionEnded       ? State::SessionEnded
                        : match->revoked          ? State::Revoked
                        : now() >= match->expires ? State::Expired
                                                  : State::Valid;
    return {state, match->session, match->number};
}

std::string InviteBook::refusal(State state) {
    switch (state) {
    case State::Valid:
        return {};
    case State::Unknown:
        return "the invite is not valid";
    case State::Expired:
        return "the invite has expired";
    case State::Revoked:
        return "the invite was revoked";
    case State::SessionEnded:
        return "the session of this invite has ended";
    }
    return "the invite is not valid";
}

bool InviteBook::revoke(const QString& session, std::uint64_t number) {
    for (Record& r : records_) {
        if (r.session == session && r.number == number) {
            r.revoked = true;
            return true;
        }
    }
    return false;
}

void InviteBook::sessionEnded(const QString& session) {
    for (Record& r : records_) {
        if (r.session == session) {
            r.sessionEnded = true;
        }
    }
    forgetOld();
}

void InviteBook::forgetOld() {
    const std::int64_t cutoff = now() - kForgetAfterSeconds;
    std::erase_if(records_, [&](const Record& r) { return r.expires < cutoff; });
}

} // namespace lucent::remote
