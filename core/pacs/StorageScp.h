#pragma once

#include <atomic>
#include <filesystem>
#include <memory>
#include <string>
#include <thread>

namespace lucent {

struct StorageScpSettings {
    std::string aeTitle = "LUCENT"; // the AE title PACS nodes send to (the C-MOVE destination)
    int port = 11112;               // 0: any free port (see StorageScp::port())
};

// Lucent's storage SCP: receives C-STORE requests (studies pushed to Lucent,
// and the sub-operations of a C-MOVE) into the study store at `storeRoot`,
// each instance written whole and moved in, on a thread of its own. Answers
// C-ECHO. Stops and joins when destroyed.
class StorageScp {
public:
    // Opens the port before returning; throws PacsError when it cannot.
    StorageScp(const std::filesystem::path& storeRoot, const StorageScpSettings& settings);
    ~StorageScp();
    StorageScp(const StorageScp&) = delete;
    StorageScp& operator=(const StorageScp&) = delete;

    int port() const { return port_; }
    const std::string& aeTitle() const { return aeTitle_; }
    int received() const { return received_.load(); }
    int failed() const { return failed_.load(); }

private:
    struct Scp;
    std::unique_ptr<Scp> scp_;
    std::string aeTitle_;
    int port_ = 0;
    std::atomic<int> received_{0};
    std::atomic<int> failed_{0};
    std::jthread thread_;
};

} // namespace lucent
