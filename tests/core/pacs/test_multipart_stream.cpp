// The incremental multipart/related parser: the same parts whatever the chunking.
#include <QDir>
#include <QFile>
#include <QTest>

#include <string>
#include <vector>

#include "core/pacs/MultipartStream.h"
#include "core/pacs/PacsNode.h"

using namespace lucent;

namespace {

std::vector<QByteArray> parse(const QByteArray& type, const QByteArray& body, qsizetype chunk) {
    MultipartStream stream(type, "test");
    std::vector<QByteArray> parts;
    stream.onPartBegin = [&] { parts.emplace_back(); };
    stream.onPartData = [&](const char* p, qsizetype n) { parts.back().append(p, n); };
    int ended = 0;
    stream.onPartEnd = [&] { ++ended; };
    for (qsizetype i = 0; i < body.size(); i += chunk) {
        stream.feed(body.constData() + i, std::min(chunk, body.size() - i));
    }
    stream.finish();
    if (ended != static_cast<int>(parts.size())) {
        throw std::runtime_error("a part did not end");
    }
    return parts;
}

} // namespace

class TestMultipartStream : public QObject {
    Q_OBJECT
private slots:
    void partsSurviveAnyChunking() {
        // Bodies that contain CR LF, dashes and most of the boundary.
        const std::vector<QByteArray> want = {QByteArray("DICM\r\n--bound\r\n-x"),
                                              QByteArray(70000, 'a') + "\r\n--boundar",
                                              QByteArray(), QByteArray("\0\1\2", 3)};
        QByteArray body = "preamble\r\n";
        for (const QByteArray& p : want) {
            body += "--boundary\r\nContent-Type: application/dicom\r\n\r\n" + p + "\r\n";
        }
        body += "--boundary--\r\n";
        for (const qsizetype chunk : {1, 2, 7, 13, 4096, 1 << 20}) {
            const auto got = parse(
                "multipart/related; type=\"application/dicom\"; boundary=boundary", body, chunk);
            QCOMPARE(got.size(), want.size());
            for (std::size_t i = 0; i < want.size(); ++i) {
                QCOMPARE(got[i], want[i]);
            }
        }
        const QByteArray quoted = "--b c\r\n\r\nxyz\r\n--b c--";
        const auto got = parse("multipart/related; boundary=\"b c\"; type=x", quoted, 3);
        QCOMPARE(got.size(), std::size_t(1));
        QCOMPARE(got[0], QByteArray("xyz"));
    }

    // fuzz_multipart: the opening delimiter without its CRLF counts only at the very
    // start; once the preamble moved on, "--b1" inside it is text, whatever the chunking.
    void boundaryInsideThePreambleIsText() {
        const QByteArray body = "xx--b1\r\n\r\nnot a part\r\n--b1\r\n\r\npart\r\n--b1--\r\n";
        for (const qsizetype chunk : {1, 3, 8, 9, 64}) {
            const auto got = parse("multipart/related; boundary=b1", body, chunk);
            QCOMPARE(got.size(), std::size_t(1));
            QCOMPARE(got[0], QByteArray("part"));
        }
    }

    // What fuzz_multipart found (fuzz-regressions/README.md): the same outcome
    // whole and in chunks of 1 to 16 bytes.
    void fuzzRegressionsGiveTheSamePartsInAnyChunks() {
        const QDir dir(QStringLiteral(LUCENT_SOURCE_DIR "/tests/core/pacs/fuzz-regressions"));
        const QStringList inputs = dir.entryList({"*.txt"}, QDir::Files);
        QVERIFY(!inputs.isEmpty());
        for (const QString& name : inputs) {
            QFile file(dir.filePath(name));
            QVERIFY(file.open(QIODevice::ReadOnly));
            const QByteArray input = file.readAll();
            const qsizetype lineEnd = input.indexOf('\n');
            QVERIFY(lineEnd >= 0 && lineEnd + 1 < input.size());
            const QByteArray type = input.left(lineEnd);
            const QByteArray body = input.mid(lineEnd + 2); // after the chunking seed
            const auto outcome = [&](qsizetype chunk) -> QString {
                try {
                    QStringList parts;
                    for (const QByteArray& p : parse(type, body, chunk)) {
                        parts << QString::fromLatin1(p.toHex());
                    }
                    return parts.join(',');
                } catch (const std::exception& e) {
                    return QStringLiteral("error: ") + e.what();
                }
            };
            const QString whole = outcome(body.size() + 1);
            for (qsizetype chunk = 1; chunk <= 16; ++chunk) {
                QVERIFY2(outcome(chunk) == whole,
                         qPrintable(name + " in chunks of " + QString::number(chunk)));
            }
        }
    }

    // Nothing after the closing delimiter is kept, however long it runs.
    void epilogueIsDropped() {
        MultipartStream stream("multipart/related; boundary=b", "test");
        const QByteArray body = "--b\r\n\r\nx\r\n--b--\r\n";
        stream.feed(body.constData(), body.size());
        const QByteArray tail(1 << 20, 'e');
        for (int i = 0; i < 64; ++i) {
            stream.feed(tail.constData(), tail.size());
        }
        stream.finish();
        QCOMPARE(stream.parts(), 1);
    }

    // A part whose headers never end is refused at 64 KiB, in one piece or in chunks.
    void endlessHeadersAreRefused() {
        const QByteArray body =
            "--b\r\nX-Padding: " + QByteArray(70000, 'p') + "\r\n\r\nx\r\n--b--";
        for (const qsizetype chunk : {1000, 1 << 20}) {
            try {
                parse("multipart/related; boundary=b", body, chunk);
                QFAIL("expected PacsError");
            } catch (const PacsError& e) {
                QVERIFY2(QString(e.what()).contains("test: the headers of part 1 run past 64 KiB"),
                         e.what());
            }
        }
    }

    void cutShortOrNotMultipartSaysSo() {
        QVERIFY_THROWS_EXCEPTION(PacsError, MultipartStream("application/dicom", "x"));
        QVERIFY_THROWS_EXCEPTION(PacsError,
                                 MultipartStream("multipart/related; boundary=\"\"", "x"));
        QVERIFY_THROWS_EXCEPTION(PacsError, MultipartStream("multipart/related; boundary=", "x"));
        QVERIFY_THROWS_EXCEPTION(
            PacsError, parse("multipart/related; boundary=b", "--b\r\n\r\nhalf a part", 5));
    }
};

QTEST_GUILESS_MAIN(TestMultipartStream)
#include "test_multipart_stream.moc"
