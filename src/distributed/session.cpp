// The MPI session of `strahl render --distributed`: MPI_Init_thread/Finalize
// around the command, the role of each rank, and the routing of errors so that
// a failure anywhere ends the whole job with one message on rank 0 and no
// output, instead of a job that hangs waiting for a rank that gave up.

#include <mpi.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <new>
#include <string>
#include <thread>

#include "fault_injection.h"
#include "protocol.h"
#include "scheduler.h"
#include "strahl/distributed/distributed.h"
#include "worker.h"

namespace strahl::distributed {

namespace {

Role currentRole = Role::Local;
bool tookPart = false;  // this rank entered renderImage

// Rank 0: prints the message and ends the job — every rank, mpirun exits 1.
[[noreturn]] void abortJob(const std::string& line) {
    std::fprintf(stderr, "%s\n", line.c_str());
    std::fflush(stderr);
    MPI_Abort(MPI_COMM_WORLD, 1);
    std::_Exit(1);  // MPI_Abort does not return; this only satisfies [[noreturn]]
}

// A worker: hands the message to rank 0, which prints it and aborts the job.
// Keeps MPI progressing (a message may still be on its way) until then.
[[noreturn]] void reportToScheduler(std::string message) {
    constexpr size_t kMaxMessage = 4000;  // one line, and small enough to send eagerly
    if (message.size() > kMaxMessage) message.resize(kMaxMessage);
    sendText(message, kSchedulerRank, kError);
    for (;;) {
        int flag = 0;
        MPI_Iprobe(kSchedulerRank, MPI_ANY_TAG, MPI_COMM_WORLD, &flag, MPI_STATUS_IGNORE);
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
}

[[noreturn]] void failRank(int rank, const std::string& message) {
    if (rank == kSchedulerRank) abortJob("strahl: error: " + message);
    reportToScheduler(message);
}

}  // namespace

bool available() { return true; }

Role role() { return currentRole; }

int run(const std::function<int()>& command) {
    int provided = 0;
    // Only a worker's main thread calls MPI; its render threads never do.
    MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided);
    int rank = 0, ranks = 0;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &ranks);
    if (provided < MPI_THREAD_FUNNELED)
        failRank(rank, "--distributed: the MPI library does not allow threads (MPI_THREAD_FUNNELED)");
    if (ranks < 2) {
        std::fprintf(stderr,
                     "strahl: error: --distributed needs at least 2 MPI processes (rank 0 "
                     "schedules, the others render), got %d: start it with mpirun -np N, N >= 2 "
                     "(docs/distributed.md)\n",
                     ranks);
        MPI_Finalize();
        return 2;
    }
    currentRole = rank == kSchedulerRank ? Role::Scheduler : Role::Worker;
    int status = 1;
    try {
        status = command();
        if (rank == kSchedulerRank) {
            if (status == 0 && !tookPart) releaseWorkers(ranks);
        } else if (status != 0) {
            failRank(rank, "stopped with exit status " + std::to_string(status));
        } else if (!tookPart) {
            sendBytes({}, kSchedulerRank, kLeave);
        }
    } catch (const WorkerFailed& e) {
        abortJob("strahl: rank " + std::to_string(e.rank()) + ": " + e.what());
    } catch (const std::bad_alloc&) {
        failRank(rank, "out of memory");
    } catch (const std::exception& e) {
        failRank(rank, e.what());
    }
    if (status != 0 && rank == kSchedulerRank) abortJob("strahl: rank 0 stopped with exit status " +
                                                        std::to_string(status));
    currentRole = Role::Local;
    MPI_Finalize();
    return status;
}

RenderStats renderImage(const World& world, const Camera& camera, const Integrator& integrator,
                        Film& film, const RenderOptions& options, const Settings& settings) {
    int rank = 0, ranks = 0;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &ranks);
    tookPart = true;
    FaultInjection fault(rank);
    if (rank == kSchedulerRank) return schedule(film, options, settings, ranks, fault);
    return work(world, camera, integrator, film, options, settings.fingerprint, fault);
}

}  // namespace strahl::distributed
