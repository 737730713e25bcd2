// Dynamic scheduling: tiles are handed out in row-major order (cutTiles), the
// same order a local render starts them in; strahl has no per-tile cost
// estimate to sort by. A request for n tiles gets min(n, max(1, remaining /
// (2 * workers))) of them — guided self-scheduling: large grants while much is
// left (few messages), single tiles at the end (no worker sits on a backlog
// while others are idle).
//
// Rank 0 waits for messages by polling (MPI_Improbe) with a sleep that grows
// to 250 us, not with a blocking receive: Open MPI spins a core in blocking
// receives, and rank 0 usually shares its node with a worker that needs the
// core. Workers ask for more tiles while they still have T queued, so the
// added latency is hidden; a result larger than the transport's eager limit
// (a few KB) does wait for rank 0's next poll before the worker's main thread
// can send the next one, which bounds the rate at which small tiles are
// gathered (docs/distributed.md#scaling).

#include "scheduler.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <span>
#include <thread>
#include <vector>

#include "protocol.h"

namespace strahl::distributed {

namespace {

using Clock = std::chrono::steady_clock;

struct WorkerState {
    bool greeted = false;  // its fingerprint was checked
    bool done = false;     // it was told no tiles are left
    int tiles = 0;         // tiles gathered from it
    int threads = 0;       // its render threads
};

Message nextMessage() {
    auto pause = std::chrono::microseconds(20);
    for (;;) {
        if (auto message = tryReceive()) return std::move(*message);
        std::this_thread::sleep_for(pause);
        pause = std::min(pause * 2, decltype(pause)(250));
    }
}

class Scheduler {
public:
    Scheduler(Film& film, const RenderOptions& options, const Settings& settings, int ranks,
              FaultInjection& fault)
        : film_(film), options_(options), settings_(settings), fault_(fault),
          tiles_(cutTiles(film.crop(), options.tileSize)), owner_(tiles_.size(), -1),
          workers_(static_cast<size_t>(ranks)) {}

    RenderStats run();

private:
    void greet(const Message& m);
    void assign(const Message& m);
    void gather(const Message& m);
    void gatherTile(int source, const ResultHeader& header, std::span<const std::byte> pixels);
    WorkerState& worker(const Message& m) { return workers_[static_cast<size_t>(m.source)]; }
    std::string rankName(int rank) const { return "rank " + std::to_string(rank); }

    Film& film_;
    const RenderOptions& options_;
    const Settings& settings_;
    FaultInjection& fault_;
    const std::vector<PixelRect> tiles_;
    std::vector<int> owner_;  // per tile: the rank it was given to, -2 once gathered
    std::vector<WorkerState> workers_;  // by rank; [0] is this scheduler
    size_t next_ = 0;                   // the next tile to hand out
    size_t gathered_ = 0;
    size_t bytes_ = 0;  // pixel state received
    RenderStats stats_;
    Clock::time_point start_;
};

void Scheduler::greet(const Message& m) {
    int32_t threads = 0;
    if (m.bytes.size() < sizeof threads) fail(rankName(m.source), " sent a truncated greeting");
    std::memcpy(&threads, m.bytes.data(), sizeof threads);
    const std::string theirs(reinterpret_cast<const char*>(m.bytes.data()) + sizeof threads,
                             m.bytes.size() - sizeof threads);
    if (theirs != settings_.fingerprint)
        fail(rankName(m.source), " was started with other settings than rank 0 (every rank must "
             "run the same command line on the same scene file): ", rankName(m.source), ": ",
             theirs, "; rank 0: ", settings_.fingerprint);
    worker(m).greeted = true;
    worker(m).threads = threads;
}

void Scheduler::assign(const Message& m) {
    WorkerState& w = worker(m);
    if (!w.greeted || w.done || m.bytes.size() != sizeof(int32_t))
        fail(rankName(m.source), " sent a tile request out of turn");
    int32_t wanted = 0;
    std::memcpy(&wanted, m.bytes.data(), sizeof wanted);
    const size_t remaining = tiles_.size() - next_;
    const size_t workers = workers_.size() - 1;
    const size_t grant = std::min(static_cast<size_t>(std::max(wanted, 1)),
                                  std::max<size_t>(1, remaining / (2 * workers)));
    std::vector<int32_t> given;
    for (; given.size() < grant && next_ < tiles_.size(); ++next_) {
        owner_[next_] = m.source;
        given.push_back(static_cast<int32_t>(next_));
    }
    if (given.empty()) w.done = true;
    sendBytes(std::as_bytes(std::span<const int32_t>(given)), m.source, kAssign);
}

void Scheduler::gather(const Message& m) {
    const std::span<const std::byte> all(m.bytes);
    for (size_t at = 0; at < all.size();) {
        ResultHeader header;
        if (all.size() - at < sizeof header) fail(rankName(m.source), " sent a truncated tile");
        std::memcpy(&header, all.data() + at, sizeof header);
        at += sizeof header;
        if (all.size() - at < header.bytes) fail(rankName(m.source), " sent a truncated tile");
        gatherTile(m.source, header, all.subspan(at, header.bytes));
        at += header.bytes;
    }
    bytes_ += m.bytes.size();
}

void Scheduler::gatherTile(int source, const ResultHeader& header,
                           std::span<const std::byte> pixels) {
    if (header.tile < 0 || static_cast<size_t>(header.tile) >= tiles_.size() ||
        owner_[static_cast<size_t>(header.tile)] != source)
        fail(rankName(source), " sent tile ", header.tile, ", which it was not given (the image has ",
             tiles_.size(), " tiles)");
    fault_.beforeTile();
    const size_t tile = static_cast<size_t>(header.tile);
    film_.unpackPixels(tiles_[tile], pixels, rankName(source) + ", tile " + std::to_string(tile));
    owner_[tile] = -2;
    ++gathered_;
    ++workers_[static_cast<size_t>(source)].tiles;
    if (gathered_ == 1)
        stats_.firstTileSeconds = std::chrono::duration<double>(Clock::now() - start_).count();
    stats_.cameraRays += header.cameraRays;
    stats_.shadowRays += header.shadowRays;
    stats_.bounceRays += header.bounceRays;
    stats_.packetWidth = header.packetWidth;
    if (options_.progress) options_.progress->advance(1);
}

RenderStats Scheduler::run() {
    start_ = Clock::now();
    if (options_.progress) options_.progress->begin("render", tiles_.size());
    const size_t workers = workers_.size() - 1;
    size_t finishedWorkers = 0;
    while (gathered_ < tiles_.size() || finishedWorkers < workers) {
        const Message m = nextMessage();
        if (m.source == kSchedulerRank) fail("rank 0 received a message from itself");
        switch (m.tag) {
            case kError: throw WorkerFailed(m.source, asText(m));
            case kHello: greet(m); break;
            case kRequest:
                assign(m);
                if (worker(m).done) ++finishedWorkers;
                break;
            case kResult: gather(m); break;
            case kLeave:
                worker(m).done = true;
                ++finishedWorkers;
                break;
            default: fail(rankName(m.source), " sent a message with unknown tag ", m.tag);
        }
        if (finishedWorkers == workers && next_ < tiles_.size())
            fail("no worker is left to render the last ", tiles_.size() - next_, " of ",
                 tiles_.size(), " tiles: the workers ended without rendering");
    }
    if (options_.progress) options_.progress->end();
    stats_.seconds = std::chrono::duration<double>(Clock::now() - start_).count();
    stats_.completedPasses = options_.spp;
    if (settings_.report) {
        std::string perRank;
        for (size_t r = 1; r < workers_.size(); ++r)
            perRank += (r > 1 ? ", " : "") + rankName(static_cast<int>(r)) + " " +
                       std::to_string(workers_[r].tiles) + " (" +
                       std::to_string(workers_[r].threads) + " threads)";
        std::fprintf(stderr,
                     "distributed: %zu tiles over %zu worker%s (tiles per rank: %s), %.1f MB of "
                     "pixel state gathered\n",
                     tiles_.size(), workers, workers == 1 ? "" : "s", perRank.c_str(),
                     static_cast<double>(bytes_) / 1e6);
    }
    return stats_;
}

}  // namespace

void releaseWorkers(int ranks) {
    std::vector<bool> released(static_cast<size_t>(ranks), false);
    for (int left = ranks - 1; left > 0;) {
        const Message m = nextMessage();
        if (m.source == kSchedulerRank || released[static_cast<size_t>(m.source)]) continue;
        switch (m.tag) {
            case kError: throw WorkerFailed(m.source, asText(m));
            case kRequest: sendBytes({}, m.source, kAssign); break;  // none left
            case kLeave: break;
            default: continue;  // its fingerprint: irrelevant, nothing is rendered
        }
        released[static_cast<size_t>(m.source)] = true;
        --left;
    }
}

RenderStats schedule(Film& film, const RenderOptions& options, const Settings& settings,
                     int ranks, FaultInjection& fault) {
    Scheduler scheduler(film, options, settings, ranks, fault);
    return scheduler.run();
}

}  // namespace strahl::distributed
