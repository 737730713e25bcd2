// A worker keeps its T render threads busy (T = --threads, or every core the
// rank may use) without ever making them call MPI: only the main thread talks
// to the scheduler (MPI_THREAD_FUNNELED). The threads take tiles from a local
// queue and put finished ones in an outbox; the main thread sleeps on a
// condition variable until there is something to send or the queue runs low,
// then ships the results and, if fewer than T tiles wait, asks for enough to
// hold 2T — so a round trip to the scheduler hides behind T tiles of work.
//
// Each tile is rendered by strahl::renderImage on a Film whose crop is the
// tile, with one thread: the very code path of a local render, so its pixels
// are the local render's bits (determinism is per pixel and sample index).

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
    FinishedTile renderTile(int index) const;
    void send(const std::deque<FinishedTile>& batch);
    void requestTiles(int count);

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
    std::deque<int> queue_;              // tiles assigned, not started
    std::deque<FinishedTile> finished_;  // rendered, not sent
    int busy_ = 0;                       // tiles being rendered
    bool noMoreTiles_ = false;           // the scheduler has none left
    bool stop_ = false;                  // a thread failed: everyone stops
    std::exception_ptr error_;
};

FinishedTile Worker::renderTile(int index) const {
    const PixelRect& rect = tiles_[static_cast<size_t>(index)];
    Film tile(film_.fullWidth(), film_.fullHeight(), rect, film_.aovs());
    if (film_.keepsHalves()) tile.keepHalves(film_.halvesFirstSample());  // --denoise
    RenderOptions options;
    options.threads = 1;  // this thread; the worker's parallelism is across tiles
    options.tileSize = options_.tileSize;
    options.spp = options_.spp;
    options.seed = options_.seed;
    options.packets = options_.packets;
    options.filter = options_.filter;
    FinishedTile done;
    done.tile = index;
    done.stats = renderImage(world_, camera_, integrator_, tile, options);
    done.pixels = tile.packPixels(rect);
    return done;
}

void Worker::renderLoop() {
    for (;;) {
        int index = 0;
        {
            std::unique_lock lock(mutex_);
            changed_.wait(lock, [&] { return stop_ || !queue_.empty() || noMoreTiles_; });
            if (stop_ || queue_.empty()) return;
            index = queue_.front();
            queue_.pop_front();
            ++busy_;
        }
        changed_.notify_all();  // the queue shrank: the main thread may ask for more
        try {
            fault_.beforeTile();
            FinishedTile done = renderTile(index);
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
    // The scheduler answers every request at once, so this wait is one round trip.
    const Message reply = receive(kSchedulerRank, kAssign);
    if (reply.bytes.size() % sizeof(int32_t) != 0)
        fail("the scheduler sent a malformed tile assignment of ", reply.bytes.size(), " bytes");
    std::vector<int32_t> assigned(reply.bytes.size() / sizeof(int32_t));
    std::memcpy(assigned.data(), reply.bytes.data(), reply.bytes.size());
    for (int32_t index : assigned)
        if (index < 0 || static_cast<size_t>(index) >= tiles_.size())
            fail("the scheduler assigned tile ", index, " of an image cut into ", tiles_.size(),
                 " tiles");
    {
        std::lock_guard lock(mutex_);
        if (assigned.empty()) noMoreTiles_ = true;
        queue_.insert(queue_.end(), assigned.begin(), assigned.end());
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
    try {
        for (;;) {
            std::unique_lock lock(mutex_);
            changed_.wait(lock, [&] { return stop_ || !finished_.empty() || wantsTiles() || idle(); });
            if (stop_) break;
            if (finished_.empty() && idle()) break;
            std::deque<FinishedTile> ship;
            ship.swap(finished_);
            const int wanted = wantsTiles() ? 2 * threads_ - static_cast<int>(queue_.size()) : 0;
            lock.unlock();
            if (!ship.empty()) send(ship);
            if (wanted > 0) requestTiles(wanted);
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
