#include "server/RecordingStore.h"

#include <QRandomGenerator>

#include <algorithm>
#include <fstream>
#include <stdexcept>

#include "protocol/Recording.h"

namespace lucent::remote {

std::string newRecordingId() {
    static constexpr char kAlphabet[] = "abcdefghijkmnpqrstuvwxyz23456789";
    std::string id;
    for (int n = 0; n < 16; ++n) {
        id += kAlphabet[QRandomGenerator::system()->bounded(32)];
    }
    return id;
}

std::filesystem::path recordingsDir(const std::filesystem::path& storeDir) {
    return storeDir / "recordings";
}

std::filesystem::path recordingFile(const std::filesystem::path& storeDir, const std::string& id) {
    return recordingsDir(storeDir) / (id + ".jsonl");
}

std::vector<RecordingSummary> listRecordings(const std::filesystem::path& storeDir) {
    std::vector<RecordingSummary> list;
    std::error_code error;
    for (const auto& entry : std::filesystem::directory_iterator(recordingsDir(storeDir), error)) {
        if (entry.path().extension() != ".jsonl") {
            continue;
        }
        try {
            const RecordingHeader h = readRecordingHeader(entry.path());
            list.push_back(
                {entry.path().stem().string(), h.series, h.durationMs, h.views, h.createdMs});
        } catch (const RecordingError&) {
            // Not a recording of this format: not listed, not replayable.
        }
    }
    std::sort(list.begin(), list.end(),
              [](const auto& a, const auto& b) { return a.created > b.created; });
    if (list.size() > kMaxListedRecordings) {
        list.resize(kMaxListedRecordings);
    }
    return list;
}

void storeRecording(const std::filesystem::path& storeDir, const std::string& id,
                    const std::string& text) {
    const std::filesystem::path temporary = storeDir / "tmp" / ("recording-" + id + ".jsonl");
    const std::filesystem::path target = recordingFile(storeDir, id);
    std::error_code error;
    std::filesystem::create_directories(temporary.parent_path(), error);
    std::filesystem::create_directories(target.parent_path(), error);
    {
        std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
        out << text;
        out.close();
        if (!out) {
            std::filesystem::remove(temporary, error);
            throw std::runtime_error(temporary.string() + ": cannot write the recording");
        }
    }
    std::filesystem::rename(temporary, target, error);
    if (error) {
        const std::string why = error.message();
        std::filesystem::remove(temporary, error);
        throw std::runtime_error(target.string() + ": cannot store the recording (" + why + ")");
    }
}

} // namespace lucent::remote
