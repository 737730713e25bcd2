// A worker keeps its T render threads busy (T = --threads, or every core the
// rank may use) without ever making them call MPI: only the main thread talks
// to the scheduler (MPI_THREAD_FUNNELED). The threads take tiles from a local
// queue and put finished ones in an outbox; the main thread sleeps on a
// condition variable until there is something to send or the queue runs low,
// then ships the results and, if fewer than T tiles wait, asks for enough to
// hold 2T — so a round trip to the scheduler hides behind T tiles of work.
// The answer may be held back (adaptive sampling: until the scheduler's round
// ends, which needs this worker's finished tiles), so the main thread never
// blocks on it: while a request is open it polls for the answer between
// shipping results, sleeping 20 us to 250 us as the scheduler does.
//
// Each tile is rendered by strahl::renderImage on a Film whose crop is the
// tile, with one thread: the very code path of a local render, so its pixels
// are the local render's bits (determinism is per pixel and sample index).
// A tile of a later adaptive round starts from the pixel state the scheduler
// sent, as a render resumed from a checkpoint does.

#include "worker.h"

#include <tbb/info.h>

#include <chrono>
#include <condition_variable>
#include <cstring>
#include <deque>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

#include "protocol.h"

namespace strahl::distributed {

namespace {

struct FinishedTile {
    int tile = 0;
    RenderStats stats;
    std::vector<std::byte> pixels;
};

class Worker {
public:
    Worker(const World& world, const Camera& camera, const Integrator& integrator,
           const Film& film, const RenderOptions& options, FaultInjection& fault)
        : world_(world), camera_(camera), integrator_(integrator), film_(film),
          options_(options), fault_(fault), tiles_(cutTiles(film.crop(), options.tileSize)),
          threads_(options.threads > 0 ? options.threads : tbb::info::default_concurrency()) {}

    RenderStats run(const std::string& fingerprint);

private:
    void renderLoop();
    FinishedTile renderTile(const TileWork& work) const;
    void send(const std::deque<FinishedTile>& batch);
    void requestTiles(int count);
    void takeAssignment(const Message& reply);

    // Under mutex_:
    bool wantsTiles() const { return !noMoreTiles_ && static_cast<int>(queue_.size()) < threads_; }
    bool idle() const { return noMoreTiles_ && queue_.empty() && busy_ == 0; }

    const World& world_;
    const Camera& camera_;
    const Integrator& integrator_;
    const Film& film_;
    const RenderOptions& options_;
    FaultInjection& fault_;
    const std::vector<PixelRect> tiles_;
    const int threads_;
    RenderStats total_;

    std::mutex mutex_;
    std::condition_variable changed_;
    std::deque<TileWork> queue_;         // tiles assigned, not started
    std::deque<FinishedTile> finished_;  // rendered, not sent
    int busy_ = 0;                       // tiles being rendered
    bool noMoreTiles_ = false;           // the scheduler has none left
    bool requestOpen_ = false;           // asked for tiles, no answer yet (main thread only)
    bool stop_ = false;                  // a thread failed: everyone stops
    std::exception_ptr error_;
};

FinishedTile Worker::renderTile(const TileWork& work) const {
    const PixelRect& rect = tiles_[static_cast<size_t>(work.tile)];
    Film tile(film_.fullWidth(), film_.fullHeight(), rect, film_.aovs());
    if (film_.keepsHalves()) tile.keepHalves(film_.halvesFirstSample());  // --denoise
    if (film_.tracksConvergence()) tile.trackConvergence();              // adaptive sampling
    if (!work.state.empty())
        tile.unpackPixels(rect, work.state, "tile " + std::to_string(work.tile) + " from rank 0");
    if (work.passEnd > options_.spp)
        fail("the scheduler asked for ", work.passEnd, " samples per pixel, more than the ",
             options_.spp, " of this render");
    RenderOptions options;
    options.threads = 1;  // this thread; the worker's parallelism is across tiles
    options.tileSize = options_.tileSize;
    // An adaptive round ends at a decision pass, which the scheduler takes
    // on the whole film: none falls inside [start, passEnd), so renderImage
    // takes no decision of its own on this tile.
    options.spp = work.passEnd;
    options.seed = options_.seed;
    options.packets = options_.packets;
    options.filter = options_.filter;
    options.adaptive = options_.adaptive;
    FinishedTile done;
    done.tile = work.tile;
    done.stats = renderImage(world_, camera_, integrator_, tile, options);
    done.pixels = tile.packPixels(rect);
    return done;
}

void Worker::renderLoop() {
    for (;;) {
        TileWork work;
        {
            std::unique_lock lock(mutex_);
            changed_.wait(lock, [&] { return stop_ || !queue_.empty() || noMoreTiles_; });
            if (stop_ || queue_.empty()) return;
            work = std::move(queue_.front());
            queue_.pop_front();
            ++busy_;
        }
        changed_.notify_all();  // the queue shrank: the main thread may ask for more
        try {
            fault_.beforeTile();
            FinishedTile done = renderTile(work);
            std::lock_guard lock(mutex_);
            finished_.push_back(std::move(done));
            --busy_;
        } catch (...) {
            std::lock_guard lock(mutex_);
            if (!error_) error_ = std::current_exception();
            stop_ = true;
            --busy_;
        }
        changed_.notify_all();
    }
}

void Worker::send(const std::deque<FinishedTile>& batch) {
    std::vector<std::byte> message;
    for (const FinishedTile& done : batch) {
        ResultHeader header;
        header.tile = done.tile;
        header.packetWidth = done.stats.packetWidth;
        header.bytes = done.pixels.size();
        header.cameraRays = done.stats.cameraRays;
        header.shadowRays = done.stats.shadowRays;
        header.bounceRays = done.stats.bounceRays;
        const auto head = asBytes(header);
        message.insert(message.end(), head.begin(), head.end());
        message.insert(message.end(), done.pixels.begin(), done.pixels.end());
        total_.cameraRays += done.stats.cameraRays;
        total_.shadowRays += done.stats.shadowRays;
        total_.bounceRays += done.stats.bounceRays;
        total_.packetWidth = done.stats.packetWidth;
    }
    sendBytes(message, kSchedulerRank, kResult);
}

void Worker::requestTiles(int count) {
    const int32_t wanted = count;
    sendBytes(asBytes(wanted), kSchedulerRank, kRequest);
    requestOpen_ = true;
}

void Worker::takeAssignment(const Message& reply) {
    if (reply.source != kSchedulerRank || reply.tag != kAssign)
        fail("rank ", reply.source, " sent this worker a message with tag ", reply.tag,
             " (only rank 0 assigns tiles)");
    std::vector<TileWork> assigned = decodeAssignment(reply.bytes, tiles_.size());
    requestOpen_ = false;
    {
        std::lock_guard lock(mutex_);
        if (assigned.empty()) noMoreTiles_ = true;
        for (TileWork& work : assigned) queue_.push_back(std::move(work));
    }
    changed_.notify_all();
}

RenderStats Worker::run(const std::string& fingerprint) {
    const auto start = std::chrono::steady_clock::now();
    const int32_t renderThreads = threads_;
    const auto head = asBytes(renderThreads);
    std::vector<std::byte> hello(head.begin(), head.end());
    for (char c : fingerprint) hello.push_back(static_cast<std::byte>(c));
    sendBytes(hello, kSchedulerRank, kHello);
    std::vector<std::thread> threads;
    threads.reserve(static_cast<size_t>(threads_));
    for (int i = 0; i < threads_; ++i) threads.emplace_back([this] { renderLoop(); });

    std::exception_ptr error;
    auto pause = std::chrono::microseconds(20);
    try {
        for (;;) {
            std::unique_lock lock(mutex_);
            const auto ready = [&] {
                return stop_ || !finished_.empty() || (wantsTiles() && !requestOpen_) || idle();
            };
            if (requestOpen_)
                changed_.wait_for(lock, pause, ready);  // then look for the answer
            else
                changed_.wait(lock, ready);
            if (stop_) break;
            if (finished_.empty() && idle()) break;
            std::deque<FinishedTile> ship;
            ship.swap(finished_);
            const int wanted = wantsTiles() && !requestOpen_
                                   ? 2 * threads_ - static_cast<int>(queue_.size())
                                   : 0;
            lock.unlock();
            if (!ship.empty()) send(ship);
            if (wanted > 0) requestTiles(wanted);
            if (requestOpen_) {
                if (auto reply = tryReceive()) {
                    takeAssignment(*reply);
                    pause = std::chrono::microseconds(20);
                } else {
                    pause = std::min(pause * 2, decltype(pause)(250));
                }
            }
        }
    } catch (...) {
        error = std::current_exception();  // an MPI-side failure of the main thread
    }
    {
        std::lock_guard lock(mutex_);
        stop_ = true;
    }
    changed_.notify_all();
    for (std::thread& thread : threads) thread.join();
    if (error_) std::rethrow_exception(error_);
    if (error) std::rethrow_exception(error);
    total_.completedPasses = options_.spp;
    total_.seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return total_;
}

}  // namespace

RenderStats work(const World& world, const Camera& camera, const Integrator& integrator,
                 const Film& film, const RenderOptions& options, const std::string& fingerprint,
                 FaultInjection& fault) {
    Worker worker(world, camera, integrator, film, options, fault);
    return worker.run(fingerprint);
}

}  // namespace strahl::distributed
