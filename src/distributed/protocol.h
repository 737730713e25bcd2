#pragma once
// The messages between the scheduler (rank 0) and the workers. Private to the
// distributed module, the only code that includes <mpi.h>.
//
// Every message is a byte array (MPI_BYTE) on MPI_COMM_WORLD; its tag says
// what it is. Ranks run the same binary on the same kind of machine (the
// film's pixel state is native-endian raw floats, like a checkpoint), so the
// headers are sent as their bytes. MPI's default error handler
// (MPI_ERRORS_ARE_FATAL) stays in place: a failed MPI call ends the job.
//
//   worker -> 0  kHello    int32 render threads, then the worker's render
//                          fingerprint (text); once, first
//   worker -> 0  kRequest  int32: how many more tiles it wants
//   0 -> worker  kAssign   tiles to render, one after the other: TileHeader
//                          (tile index into cutTiles(crop, tile size), the
//                          pass to render up to, `bytes`), then its `bytes`
//                          bytes of Film::packPixels to start from (none: an
//                          empty tile, all passes from 0); no tiles at all:
//                          none are left, the worker is done. The scheduler
//                          may hold a request back (adaptive sampling: until
//                          the round's decisions are taken), so a worker
//                          never blocks on the answer: it keeps sending
//                          finished tiles meanwhile
//   worker -> 0  kResult   finished tiles, one after the other: ResultHeader,
//                          then its `bytes` bytes of Film::packPixels (one
//                          message carries every tile finished since the last,
//                          so the per-message latency is paid once per batch)
//   worker -> 0  kError    the message of the error that stopped the worker
//   worker -> 0  kLeave    (empty) the command ended on this worker without
//                          rendering (it found nothing to do): it takes no tiles
//
// Every worker ends its part with exactly one of: an empty kAssign (after
// which it only sends the results of the tiles it still holds), kError or
// kLeave — so rank 0 always knows when no more messages will come, and a job
// cannot hang on a rank that went its own way.

#include <mpi.h>

#include <cstddef>
#include <cstdint>
#include <deque>
#include <optional>
#include <span>
#include <string>
#include <type_traits>
#include <vector>

#include "strahl/core/error.h"

namespace strahl::distributed {

enum Tag : int { kHello = 1, kRequest = 2, kAssign = 3, kResult = 4, kError = 5, kLeave = 6 };

inline constexpr int kSchedulerRank = 0;

struct TileHeader {
    int32_t tile = 0;
    int32_t passEnd = 0;  // render the tile's pixels up to this many samples
    uint64_t bytes = 0;   // of pixel state following the header
};
static_assert(std::is_trivially_copyable_v<TileHeader>, "sent as raw bytes");

// One tile of an assignment: the work of a worker.
struct TileWork {
    int tile = 0;
    int passEnd = 0;
    std::vector<std::byte> state;  // empty: start from an empty film
};

// kAssign's bytes <-> its tiles. decodeAssignment throws strahl::Error for a
// truncated message, a tile index outside [0, tileCount) or passEnd < 1.
std::vector<std::byte> encodeAssignment(const std::vector<TileWork>& tiles);
std::vector<TileWork> decodeAssignment(std::span<const std::byte> bytes, size_t tileCount);

struct ResultHeader {
    int32_t tile = 0;
    int32_t packetWidth = 0;
    uint64_t bytes = 0;  // of pixel state following the header
    uint64_t cameraRays = 0, shadowRays = 0, bounceRays = 0;
};
static_assert(std::is_trivially_copyable_v<ResultHeader>, "sent as raw bytes");

struct Message {
    int source = 0;
    int tag = 0;
    std::vector<std::byte> bytes;
};

// A worker's failure, raised on the scheduler: run() prints it as
// "strahl: rank K: <message>" rather than as rank 0's own error.
class WorkerFailed : public Error {
public:
    WorkerFailed(int rank, const std::string& message) : Error(message), rank_(rank) {}
    int rank() const { return rank_; }

private:
    int rank_;
};

// Blocking send of `bytes` (at most INT_MAX of them: MPI counts are int).
void sendBytes(std::span<const std::byte> bytes, int destination, Tag tag);
void sendText(const std::string& text, int destination, Tag tag);

// Sends that never wait for the receiver (MPI_Isend), for rank 0: a worker
// blocks in its send of a large result (beyond the eager limit) until rank 0
// receives it, so rank 0 must never itself block in a send of a large
// assignment to that worker. Messages to one rank still arrive in the order
// sent (MPI's non-overtaking rule). If the job fails first, MPI_Abort ends it
// with sends pending; nothing waits for them.
class AsyncSends {
public:
    AsyncSends() = default;
    AsyncSends(const AsyncSends&) = delete;
    AsyncSends& operator=(const AsyncSends&) = delete;

    void send(std::vector<std::byte> bytes, int destination, Tag tag);
    // Releases the buffers of the sends that have completed; never blocks.
    void progress();
    // Waits until every send has completed (their receivers must be receiving).
    void finish();

private:
    struct Pending {
        MPI_Request request;
        std::vector<std::byte> bytes;  // must live until the send completes
    };
    std::deque<Pending> pending_;
};

// A message from anyone, if one has arrived (MPI_Improbe + MPI_Mrecv, so the
// probed message is the one received). Never blocks.
std::optional<Message> tryReceive();
// Blocks until a message with `tag` from `source` arrives.
Message receive(int source, Tag tag);

// Bytes <-> trivially copyable values.
template <typename T>
std::span<const std::byte> asBytes(const T& value) {
    return std::as_bytes(std::span<const T, 1>(&value, 1));
}
std::string asText(const Message& message);

}  // namespace strahl::distributed
