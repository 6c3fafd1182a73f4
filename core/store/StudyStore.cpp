#include "core/store/StudyStore.h"

#include <atomic>
#include <cctype>
#include <chrono>
#include <system_error>
#include <thread>

#include <QSqlDatabase>
#include <QSqlError>
#include <QSqlQuery>
#include <QString>
#include <QVariant>

#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <cstring>

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

namespace lucent {
namespace {

namespace fs = std::filesystem;

QString q(const std::string& s) {
    return QString::fromStdString(s);
}

// A UID is digits and dots; anything else must not reach a path.
std::string safeComponent(const std::string& uid) {
    std::string out;
    for (const char c : uid) {
        out += (std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '-') ? c : '_';
    }
    return out.empty() ? std::string("unknown") : out;
}

QSqlQuery prepared(const std::string& connection, const char* sql) {
    QSqlQuery query(QSqlDatabase::database(q(connection)));
    if (!query.prepare(sql)) {
        throw StoreError(std::string("study index: ") + query.lastError().text().toStdString());
    }
    return query;
}

// Runs a prepared statement, or `sql` when given. Another connection (the
// storage SCP, a retrieval, the study browser) may hold the index for a moment
// longer than SQLite's own wait, and some statements, such as switching to WAL,
// do not wait at all: "locked" or "busy" is tried again for up to 5 s more.
void run(QSqlQuery& query, const fs::path& root, const QString& sql = {}) {
    for (int attempt = 0;; ++attempt) {
        if (sql.isEmpty() ? query.exec() : query.exec(sql)) {
            return;
        }
        const QString error = query.lastError().text();
        if (attempt < 250 && (error.contains("locked") || error.contains("busy"))) {
            std::this_thread::sleep_for(std::chrono::milliseconds(20));
            continue;
        }
        throw StoreError(root.string() + "/index.sqlite: " + error.toStdString());
    }
}

// True when a temporary file's name says a running process writes it
// (incoming-<pid>-<store>-<n>.dcm).
bool writerAlive(const std::string& name) {
    const std::string prefix = "incoming-";
    if (name.rfind(prefix, 0) != 0) {
        return false;
    }
    const long pid = std::strtol(name.c_str() + prefix.size(), nullptr, 10);
    return pid > 0 && (::kill(static_cast<pid_t>(pid), 0) == 0 || errno == EPERM);
}

// Held while a connection sets the index up, across threads and processes:
// the first to open a new store switches it to WAL and creates the tables
// while the others wait. Two openers at once otherwise lock each other out in
// rollback mode, and SQLite answers a WAL switch it could not make with the
// old mode instead of an error. The kernel drops the lock if a process dies.
class SetupLock {
public:
    explicit SetupLock(const fs::path& file)
        : fd_(::open(file.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644)) {
        if (fd_ < 0) {
            throw StoreError(file.string() + ": cannot open the store's lock file (" +
                             std::strerror(errno) + ")");
        }
        while (::flock(fd_, LOCK_EX) != 0 && errno == EINTR) {
        }
    }
    ~SetupLock() { ::close(fd_); }
    SetupLock(const SetupLock&) = delete;
    SetupLock& operator=(const SetupLock&) = delete;

private:
    int fd_;
};

} // namespace

StudyStore::StudyStore(const fs::path& root) : root_(root) {
    static std::atomic<int> instances{0};
    const std::string self = std::to_string(::getpid()) + "-" + std::to_string(++instances);
    connection_ = "lucent-store-" + self;
    tempPrefix_ = "incoming-" + self + "-";
    std::error_code ec;
    fs::create_directories(root_ / "files", ec);
    fs::create_directories(root_ / "tmp", ec);
    if (ec || !fs::is_directory(root_ / "files")) {
        throw StoreError(root_.string() + ": cannot create the store folder (" + ec.message() +
                         ")");
    }
    // Leftovers of writes that never finished: never indexed, never in files/.
    // Files of a process still running (this one included: the storage SCP, a
    // retrieval) are being written now and stay.
    for (const auto& e : fs::directory_iterator(root_ / "tmp", ec)) {
        if (!writerAlive(e.path().filename().string())) {
            fs::remove(e.path(), ec);
        }
    }
    const SetupLock setup(root_ / "index.lock");
    QSqlDatabase db = QSqlDatabase::addDatabase("QSQLITE", q(connection_));
    db.setDatabaseName(q((root_ / "index.sqlite").string()));
    if (!db.open()) {
        throw StoreError(root_.string() + "/index.sqlite: " + db.lastError().text().toStdString() +
                         " (is the Qt SQLite driver, libqt6sql6-sqlite, installed?)");
    }
    QSqlQuery wal(db);
    run(wal, root_, "PRAGMA journal_mode=WAL");
    if (!wal.next() || wal.value(0).toString() != "wal") {
        throw StoreError(root_.string() + "/index.sqlite: cannot switch the index to write-ahead " +
                         "logging (journal mode '" + wal.value(0).toString().toStdString() +
                         "'); is the store on a file system without shared memory, such as NFS?");
    }
    wal.finish();
    // WAL with NORMAL sync stays consistent after a crash; a power loss can only
    // drop the last few index rows, whose instances the next retrieval fetches
    // again. FULL would fsync for every instance of a retrieval.
    exec("PRAGMA synchronous=NORMAL");
    exec("CREATE TABLE IF NOT EXISTS patients (patient_key TEXT PRIMARY KEY, patient_id TEXT, "
         "patient_name TEXT, birth_date TEXT)");
    exec("CREATE TABLE IF NOT EXISTS studies (study_uid TEXT PRIMARY KEY, patient_key TEXT, "
         "study_date TEXT, study_description TEXT, accession TEXT)");
    exec("CREATE TABLE IF NOT EXISTS series (series_uid TEXT PRIMARY KEY, study_uid TEXT, "
         "patient_id TEXT, patient_name TEXT, study_date TEXT, series_description TEXT, modality "
         "TEXT, series_number INTEGER, expected INTEGER DEFAULT 0)");
    exec(
        "CREATE TABLE IF NOT EXISTS instances (sop_uid TEXT PRIMARY KEY, series_uid TEXT NOT NULL, "
        "path TEXT NOT NULL)");
    exec("CREATE TABLE IF NOT EXISTS series_offsets (series_a TEXT NOT NULL, series_b TEXT NOT "
         "NULL, dx REAL, dy REAL, dz REAL, PRIMARY KEY (series_a, series_b))");
    // A registration's rigid transform a -> b (16 numbers, row-major) per series pair.
    exec("CREATE TABLE IF NOT EXISTS series_transforms (series_a TEXT NOT NULL, series_b TEXT "
         "NOT NULL, matrix TEXT NOT NULL, PRIMARY KEY (series_a, series_b))");
    exec("CREATE INDEX IF NOT EXISTS instances_by_series ON instances(series_uid)");
    // Stores from before the patients and studies tables (schema version 0):
    // fill them from the series, once. Opening a current store writes nothing.
    QSqlQuery version(QSqlDatabase::database(q(connection_)));
    if (version.exec("PRAGMA user_version") && version.next() && version.value(0).toInt() < 1) {
        exec("INSERT OR IGNORE INTO patients (patient_key, patient_id, patient_name, birth_date) "
             "SELECT patient_id || '|' || patient_name, patient_id, patient_name, '' FROM series");
        exec("INSERT OR IGNORE INTO studies (study_uid, patient_key, study_date, "
             "study_description, accession) SELECT study_uid, patient_id || '|' || "
             "patient_name, study_date, '', '' FROM series");
        exec("PRAGMA user_version = 1");
    }
}

StudyStore::~StudyStore() {
    {
        QSqlDatabase db = QSqlDatabase::database(q(connection_), false);
        db.close();
    }
    QSqlDatabase::removeDatabase(q(connection_));
}

void StudyStore::exec(const std::string& sql) const {
    QSqlQuery query(QSqlDatabase::database(q(connection_)));
    run(query, root_, q(sql));
}

fs::path StudyStore::temporaryFile() {
    return root_ / "tmp" / (tempPrefix_ + std::to_string(++counter_) + ".dcm");
}

bool StudyStore::contains(const std::string& sop) const {
    QSqlQuery query = prepared(connection_, "SELECT 1 FROM instances WHERE sop_uid = ?");
    query.addBindValue(q(sop));
    run(query, root_);
    return query.next();
}

std::set<std::string> StudyStore::instancesOf(const std::string& seriesUid) const {
    QSqlQuery query = prepared(connection_, "SELECT sop_uid FROM instances WHERE series_uid = ?");
    query.addBindValue(q(seriesUid));
    run(query, root_);
    std::set<std::string> out;
    while (query.next()) {
        out.insert(query.value(0).toString().toStdString());
    }
    return out;
}

fs::path StudyStore::seriesFolder(const std::string& studyUid, const std::string& seriesUid) const {
    return root_ / "files" / safeComponent(studyUid) / safeComponent(seriesUid);
}

bool StudyStore::add(const fs::path& file, const InstanceRecord& r) {
    std::error_code ec;
    if (r.sopInstanceUid.empty() || r.series.seriesUid.empty() || r.series.studyUid.empty()) {
        fs::remove(file, ec);
        throw StoreError(file.string() +
                         ": an instance without study, series or SOP instance UID is not stored");
    }
    if (contains(r.sopInstanceUid)) {
        fs::remove(file, ec);
        return false;
    }
    const fs::path folder = seriesFolder(r.series.studyUid, r.series.seriesUid);
    fs::create_directories(folder, ec);
    const fs::path target = folder / (safeComponent(r.sopInstanceUid) + ".dcm");
    fs::rename(file, target, ec); // same file system: atomic
    if (ec) {
        fs::remove(file, ec);
        throw StoreError(target.string() + ": cannot move the received file into the store (" +
                         ec.message() + ")");
    }
    if (batchDepth_ > 0) {
        uncommitted_.push_back(target);
    }
    try {
        indexInstance(target, r);
    } catch (const StoreError& e) {
        // Not indexed (or its batch rolled back): the file goes too.
        fs::remove(target, ec);
        dropUncommitted(true);
        throw writeError(root_ / "index.sqlite", e.what());
    }
    // A long retrieval commits now and then, so that other connections (the
    // storage SCP, the study browser) are not kept waiting for the write lock.
    if (batchDepth_ > 0 && ++batchAdds_ % 32 == 0) {
        commitBatch(true);
    }
    return true;
}

void StudyStore::indexInstance(const fs::path& target, const InstanceRecord& r) {
    QSqlQuery series =
        prepared(connection_,
                 "INSERT INTO series (series_uid, study_uid, patient_id, patient_name, study_date, "
                 "series_description, modality, series_number) VALUES (?,?,?,?,?,?,?,?) "
                 "ON CONFLICT(series_uid) DO NOTHING");
    for (const std::string* v :
         {&r.series.seriesUid, &r.series.studyUid, &r.series.patientId, &r.series.patientName,
          &r.series.studyDate, &r.series.description, &r.series.modality}) {
        series.addBindValue(q(*v));
    }
    series.addBindValue(r.seriesNumber);
    run(series, root_);
    upsertStudy(r);
    QSqlQuery instance =
        prepared(connection_, "INSERT INTO instances (sop_uid, series_uid, path) VALUES (?,?,?)");
    instance.addBindValue(q(r.sopInstanceUid));
    instance.addBindValue(q(r.series.seriesUid));
    instance.addBindValue(q((fs::path("files") / safeComponent(r.series.studyUid) /
                             safeComponent(r.series.seriesUid) / target.filename())
                                .string()));
    run(instance, root_);
}

void StudyStore::remove(const std::string& sop) {
    QSqlQuery path =
        prepared(connection_, "SELECT path, series_uid FROM instances WHERE sop_uid = ?");
    path.addBindValue(q(sop));
    run(path, root_);
    std::string seriesUid;
    if (path.next()) {
        std::error_code ec;
        fs::remove(root_ / path.value(0).toString().toStdString(), ec);
        seriesUid = path.value(1).toString().toStdString();
    }
    // Its read snapshot ends here: a DELETE on a stale snapshot would be
    // refused as "locked" however long it waited.
    path.finish();
    QSqlQuery del = prepared(connection_, "DELETE FROM instances WHERE sop_uid = ?");
    del.addBindValue(q(sop));
    run(del, root_);
    // A series no PACS listed (pushed, or Lucent's own SR) goes with its last
    // instance; one a retrieval expects stays, incomplete, to be fetched again.
    QSqlQuery empty =
        prepared(connection_, "DELETE FROM series WHERE series_uid = ? AND expected = 0 AND NOT "
                              "EXISTS (SELECT 1 FROM instances WHERE series_uid = ?)");
    empty.addBindValue(q(seriesUid));
    empty.addBindValue(q(seriesUid));
    run(empty, root_);
}

void StudyStore::setExpected(const SeriesInfo& s, int seriesNumber, int instances) {
    InstanceRecord r;
    r.series = s;
    r.seriesNumber = seriesNumber;
    setExpected(r, instances);
}

void StudyStore::setExpected(const InstanceRecord& r, int instances) {
    const SeriesInfo& s = r.series;
    QSqlQuery query = prepared(
        connection_,
        "INSERT INTO series (series_uid, study_uid, patient_id, patient_name, study_date, "
        "series_description, modality, series_number, expected) VALUES (?,?,?,?,?,?,?,?,?) "
        "ON CONFLICT(series_uid) DO UPDATE SET expected = excluded.expected");
    for (const std::string* v : {&s.seriesUid, &s.studyUid, &s.patientId, &s.patientName,
                                 &s.studyDate, &s.description, &s.modality}) {
        query.addBindValue(q(*v));
    }
    query.addBindValue(r.seriesNumber);
    query.addBindValue(instances);
    run(query, root_);
    upsertStudy(r);
}

void StudyStore::upsertStudy(const InstanceRecord& r) {
    const QString key = q(r.series.patientId + "|" + r.series.patientName);
    QSqlQuery patient = prepared(
        connection_, "INSERT INTO patients (patient_key, patient_id, patient_name, birth_date) "
                     "VALUES (?,?,?,?) ON CONFLICT(patient_key) DO UPDATE SET birth_date = "
                     "excluded.birth_date WHERE excluded.birth_date <> ''");
    patient.addBindValue(key);
    patient.addBindValue(q(r.series.patientId));
    patient.addBindValue(q(r.series.patientName));
    patient.addBindValue(q(r.patientBirthDate));
    run(patient, root_);
    QSqlQuery study = prepared(
        connection_,
        "INSERT INTO studies (study_uid, patient_key, study_date, study_description, accession) "
        "VALUES (?,?,?,?,?) ON CONFLICT(study_uid) DO UPDATE SET "
        "study_description = CASE WHEN excluded.study_description <> '' THEN "
        "excluded.study_description ELSE study_description END, "
        "accession = CASE WHEN excluded.accession <> '' THEN excluded.accession ELSE accession "
        "END");
    study.addBindValue(q(r.series.studyUid));
    study.addBindValue(key);
    study.addBindValue(q(r.series.studyDate));
    study.addBindValue(q(r.studyDescription));
    study.addBindValue(q(r.accessionNumber));
    run(study, root_);
}

InstanceRecord StudyStore::recordBeside(const std::string& seriesUid) const {
    InstanceRecord record;
    for (const StoredSeries& s : listSeries()) {
        if (s.info.seriesUid == seriesUid) {
            record.series = s.info;
            record.studyDescription = s.studyDescription;
            record.accessionNumber = s.accessionNumber;
            record.patientBirthDate = s.patientBirthDate;
        }
    }
    return record;
}

std::vector<StoredSeries> StudyStore::listSeries() const {
    QSqlQuery query = prepared(
        connection_,
        "SELECT s.series_uid, s.study_uid, s.modality, s.series_description, p.patient_name, "
        "p.patient_id, st.study_date, st.study_description, st.accession, p.birth_date, "
        "s.series_number, s.expected, (SELECT COUNT(*) FROM instances i WHERE i.series_uid = "
        "s.series_uid) FROM series s JOIN studies st ON st.study_uid = s.study_uid JOIN patients "
        "p ON p.patient_key = st.patient_key ORDER BY p.patient_name, st.study_date, "
        "s.study_uid, s.series_number, s.series_uid");
    run(query, root_);
    std::vector<StoredSeries> out;
    while (query.next()) {
        StoredSeries s;
        auto text = [&](int i) { return query.value(i).toString().toStdString(); };
        s.info.seriesUid = text(0);
        s.info.studyUid = text(1);
        s.info.modality = text(2);
        s.info.description = text(3);
        s.info.patientName = text(4);
        s.info.patientId = text(5);
        s.info.studyDate = text(6);
        s.studyDescription = text(7);
        s.accessionNumber = text(8);
        s.patientBirthDate = text(9);
        s.seriesNumber = query.value(10).toInt();
        s.expected = query.value(11).toInt();
        s.stored = query.value(12).toInt();
        s.complete = s.expected > 0 && s.stored >= s.expected;
        s.folder = seriesFolder(s.info.studyUid, s.info.seriesUid);
        out.push_back(std::move(s));
    }
    return out;
}

int StudyStore::expected(const std::string& seriesUid) const {
    QSqlQuery query = prepared(connection_, "SELECT expected FROM series WHERE series_uid = ?");
    query.addBindValue(q(seriesUid));
    run(query, root_);
    return query.next() ? query.value(0).toInt() : 0;
}

bool StudyStore::isComplete(const std::string& seriesUid) const {
    const int want = expected(seriesUid);
    return want > 0 && static_cast<int>(instancesOf(seriesUid).size()) >= want;
}

} // namespace lucent
