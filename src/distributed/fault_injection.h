#pragma once
// A test hook for the failure of a whole process (docs/distributed.md#failures):
// STRAHL_DISTRIBUTED_FAULT=RANK:TILES makes rank RANK kill itself with SIGKILL
// (as the kernel's OOM killer or a crashed node would) once it has handled
// TILES tiles: a worker just before it starts rendering its tile number TILES
// (counting from 0), the scheduler just before it gathers tile number TILES.
// Read only here; unset, it does nothing. A malformed value is an error.

#include <atomic>
#include <optional>

namespace strahl::distributed {

class FaultInjection {
public:
    // Reads STRAHL_DISTRIBUTED_FAULT for this rank.
    explicit FaultInjection(int rank);

    // Counts one more tile handled by this rank; dies first if it is the one
    // the hook names. Thread-safe.
    void beforeTile();

private:
    std::optional<long> dieAt_;  // tiles this rank handles before it dies
    std::atomic<long> handled_{0};
};

}  // namespace strahl::distributed
