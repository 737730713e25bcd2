// Dynamic scheduling: tiles are handed out in row-major order (cutTiles), the
// same order a local render starts them in; strahl has no per-tile cost
// estimate to sort by. A request for n tiles gets min(n, max(1, remaining /
// (2 * workers))) of them — guided self-scheduling: large grants while much is
// left (few messages), single tiles at the end (no worker sits on a backlog
// while others are idle).
//
// Rounds. Without adaptive sampling there is one: every tile, all its passes,
// from an empty film. With it (docs/adaptive.md) the passes are cut at the
// decision passes (isDecisionPass): a round renders each tile that still has
// a running pixel up to the next decision pass, starting from the pixel state
// rank 0 sends with it, and when every tile of the round is back, rank 0
// takes the decisions on its whole film (stopConvergedPixels) — the same
// decisions, from the same film, at the same passes as a local render, so the
// image is the local image bit for bit. Requests that come while a round
// drains are answered when the next one starts; a worker keeps sending the
// tiles it finishes meanwhile, so waiting costs no deadlock, only the idle
// time of the round's last tiles.
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
#include <deque>
#include <span>
#include <thread>
#include <vector>

#include "protocol.h"
#include "strahl/render/adaptive_sampling.h"

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
    void request(const Message& m);
    void serveRequests();
    bool startRound(int passStart);
    void endRound();
    void gather(const Message& m);
    void gatherTile(int source, const ResultHeader& header, std::span<const std::byte> pixels);
    WorkerState& worker(const Message& m) { return workers_[static_cast<size_t>(m.source)]; }
    std::string rankName(int rank) const { return "rank " + std::to_string(rank); }

    Film& film_;
    const RenderOptions& options_;
    const Settings& settings_;
    FaultInjection& fault_;
    const std::vector<PixelRect> tiles_;
    std::vector<int> owner_;  // per tile: the rank it was given to this round, -2 once gathered
    std::vector<WorkerState> workers_;  // by rank; [0] is this scheduler
    struct Request {
        int rank = 0;
        int wanted = 0;
    };
    std::deque<Request> waiting_;  // requests not answered yet (arrival order)
    AsyncSends sends_;             // assignments on their way
    std::vector<int> round_;       // the tiles of this round
    int passStart_ = 0;            // this round renders from this pass ...
    int passEnd_ = 0;              // ... up to this one
    bool finished_ = false;        // no round is left: requests get "none left"
    size_t next_ = 0;              // the next tile of round_ to hand out
    size_t gathered_ = 0;          // tiles of round_ back
    size_t roundsTiles_ = 0;       // tiles gathered over all rounds
    size_t bytes_ = 0;      // pixel state received
    size_t sentBytes_ = 0;  // pixel state sent (adaptive sampling's later rounds)
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

void Scheduler::request(const Message& m) {
    WorkerState& w = worker(m);
    if (!w.greeted || w.done || m.bytes.size() != sizeof(int32_t))
        fail(rankName(m.source), " sent a tile request out of turn");
    for (const Request& r : waiting_)
        if (r.rank == m.source) fail(rankName(m.source), " sent a tile request out of turn");
    int32_t wanted = 0;
    std::memcpy(&wanted, m.bytes.data(), sizeof wanted);
    waiting_.push_back({m.source, std::max(wanted, 1)});
}

void Scheduler::serveRequests() {
    const size_t workers = workers_.size() - 1;
    while (!waiting_.empty() && (finished_ || next_ < round_.size())) {
        const Request r = waiting_.front();
        waiting_.pop_front();
        const size_t remaining = round_.size() - next_;
        const size_t grant = std::min(static_cast<size_t>(r.wanted),
                                      std::max<size_t>(1, remaining / (2 * workers)));
        std::vector<TileWork> given;
        for (; given.size() < grant && next_ < round_.size(); ++next_) {
            const int tile = round_[next_];
            owner_[static_cast<size_t>(tile)] = r.rank;
            TileWork work;
            work.tile = tile;
            work.passEnd = passEnd_;
            // The first round starts from an empty film: nothing to send.
            if (passStart_ > 0)
                work.state = film_.packPixels(tiles_[static_cast<size_t>(tile)]);
            given.push_back(std::move(work));
        }
        if (given.empty()) workers_[static_cast<size_t>(r.rank)].done = true;
        for (const TileWork& work : given) sentBytes_ += work.state.size();
        sends_.send(encodeAssignment(given), r.rank, kAssign);
    }
}

// The tiles that still have a running pixel, up to the next decision pass
// after passStart (or spp); false if there are none.
bool Scheduler::startRound(int passStart) {
    int end = passStart + 1;
    if (film_.tracksConvergence())
        while (end < options_.spp && !isDecisionPass(end, options_.adaptive.minSamples)) ++end;
    else
        end = options_.spp;
    round_.clear();
    for (size_t i = 0; i < tiles_.size(); ++i) {
        bool running = !film_.tracksConvergence();
        const PixelRect& t = tiles_[i];
        for (int y = t.y0; y < t.y1 && !running; ++y)
            for (int x = t.x0; x < t.x1 && !running; ++x) running = !film_.converged(x, y);
        if (running) round_.push_back(static_cast<int>(i));
        owner_[i] = -1;
    }
    passStart_ = passStart;
    passEnd_ = end;
    next_ = 0;
    gathered_ = 0;
    return !round_.empty();
}

// Every tile of the round is back: the decisions at its end pass, then the
// next round, or the end.
void Scheduler::endRound() {
    stats_.completedPasses = passEnd_;
    if (passEnd_ < options_.spp && stopConvergedPixels(film_, options_.adaptive) == 0)
        stats_.converged = true;  // every pixel stopped before spp
    if (stats_.converged || passEnd_ == options_.spp || !startRound(passEnd_)) finished_ = true;
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
        owner_[static_cast<size_t>(header.tile)] != source || finished_)
        fail(rankName(source), " sent tile ", header.tile, ", which it was not given (the image has ",
             tiles_.size(), " tiles)");
    fault_.beforeTile();
    const size_t tile = static_cast<size_t>(header.tile);
    film_.unpackPixels(tiles_[tile], pixels, rankName(source) + ", tile " + std::to_string(tile));
    owner_[tile] = -2;
    ++gathered_;
    ++roundsTiles_;
    ++workers_[static_cast<size_t>(source)].tiles;
    if (roundsTiles_ == 1)
        stats_.firstTileSeconds = std::chrono::duration<double>(Clock::now() - start_).count();
    stats_.cameraRays += header.cameraRays;
    stats_.shadowRays += header.shadowRays;
    stats_.bounceRays += header.bounceRays;
    stats_.packetWidth = header.packetWidth;
    if (options_.progress) options_.progress->advance(1);
}

RenderStats Scheduler::run() {
    start_ = Clock::now();
    if (film_.tracksConvergence() &&
        (options_.adaptive.minSamples < 2 || !options_.adaptive.enabled()))
        fail("adaptive sampling needs a threshold above 0 and at least 2 samples before it stops "
             "a pixel");
    finished_ = !startRound(0);
    // Progress counts tile rounds: with adaptive sampling an upper bound
    // (every tile in every round), passed short when pixels stop, as a local
    // render's count of tile passes is.
    size_t rounds = 1;
    if (film_.tracksConvergence()) {
        rounds = 0;
        for (int pass = 1; pass <= options_.spp; ++pass)
            if (pass == options_.spp || isDecisionPass(pass, options_.adaptive.minSamples)) ++rounds;
    }
    if (options_.progress) options_.progress->begin("render", tiles_.size() * rounds);
    const size_t workers = workers_.size() - 1;
    size_t finishedWorkers = 0;
    while (!finished_ || finishedWorkers < workers) {
        const Message m = nextMessage();
        if (m.source == kSchedulerRank) fail("rank 0 received a message from itself");
        switch (m.tag) {
            case kError: throw WorkerFailed(m.source, asText(m));
            case kHello: greet(m); break;
            case kRequest: request(m); break;
            case kResult:
                gather(m);
                if (!finished_ && gathered_ == round_.size()) endRound();
                break;
            case kLeave: worker(m).done = true; break;
            default: fail(rankName(m.source), " sent a message with unknown tag ", m.tag);
        }
        serveRequests();  // a new request, or a new round for the waiting ones
        sends_.progress();
        finishedWorkers = 0;
        for (size_t r = 1; r < workers_.size(); ++r) finishedWorkers += workers_[r].done;
        if (finishedWorkers == workers && !finished_)
            fail("no worker is left to render the last ", round_.size() - gathered_, " of ",
                 round_.size(), " tiles: the workers ended without rendering");
    }
    sends_.finish();  // the last answers ("none left") reach workers that are polling for them
    if (options_.progress) options_.progress->end();
    stats_.seconds = std::chrono::duration<double>(Clock::now() - start_).count();
    if (!film_.tracksConvergence()) stats_.completedPasses = options_.spp;
    if (settings_.report) {
        std::string perRank;
        for (size_t r = 1; r < workers_.size(); ++r)
            perRank += (r > 1 ? ", " : "") + rankName(static_cast<int>(r)) + " " +
                       std::to_string(workers_[r].tiles) + " (" +
                       std::to_string(workers_[r].threads) + " threads)";
        char sent[64] = "";
        if (sentBytes_)
            std::snprintf(sent, sizeof sent, ", %.1f MB sent", static_cast<double>(sentBytes_) / 1e6);
        std::fprintf(stderr,
                     "distributed: %zu tiles over %zu worker%s (tiles per rank: %s), %.1f MB of "
                     "pixel state gathered%s\n",
                     roundsTiles_, workers, workers == 1 ? "" : "s", perRank.c_str(),
                     static_cast<double>(bytes_) / 1e6, sent);
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
