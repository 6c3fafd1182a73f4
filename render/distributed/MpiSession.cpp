#include "render/distributed/MpiSession.h"

#include <mpi.h>

#include <stdexcept>
#include <string>

namespace lucent {

namespace {
bool g_session = false;
} // namespace

MpiSession::MpiSession(MpiThreads threads) {
    if (g_session) {
        throw std::runtime_error("MPI: a second MpiSession in one process");
    }
    int initialised = 0;
    MPI_Initialized(&initialised);
    if (initialised == 0) {
        const int wanted =
            threads == MpiThreads::Serialised ? MPI_THREAD_SERIALIZED : MPI_THREAD_FUNNELED;
        int provided = 0;
        if (MPI_Init_thread(nullptr, nullptr, wanted, &provided) != MPI_SUCCESS) {
            throw std::runtime_error("MPI: MPI_Init_thread failed");
        }
        if (provided < wanted) {
            MPI_Finalize();
            throw std::runtime_error("MPI: the library gives thread level " +
                                     std::to_string(provided) + ", not " +
                                     (threads == MpiThreads::Serialised ? "MPI_THREAD_SERIALIZED"
                                                                        : "MPI_THREAD_FUNNELED"));
        }
    }
    // Errors come back as codes, so that they can be reported with the rank.
    MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN);
    MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
    MPI_Comm_size(MPI_COMM_WORLD, &size_);
    g_session = true;
}

MpiSession::~MpiSession() {
    g_session = false;
    int finalised = 0;
    MPI_Finalized(&finalised);
    if (finalised == 0) {
        MPI_Finalize();
    }
}

bool MpiSession::active() {
    int initialised = 0, finalised = 0;
    MPI_Initialized(&initialised);
    MPI_Finalized(&finalised);
    return initialised != 0 && finalised == 0;
}

} // namespace lucent
