#include "fault_injection.h"

#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "strahl/core/error.h"

namespace strahl::distributed {

FaultInjection::FaultInjection(int rank) {
    const char* value = std::getenv("STRAHL_DISTRIBUTED_FAULT");
    if (value == nullptr || *value == '\0') return;
    int faultRank = -1;
    long tiles = -1;
    char tail = 0;
    if (std::sscanf(value, "%d:%ld%c", &faultRank, &tiles, &tail) != 2 || faultRank < 0 ||
        tiles < 0)
        fail("STRAHL_DISTRIBUTED_FAULT: expected RANK:TILES (two integers >= 0), got '", value,
             "'");
    if (faultRank == rank) dieAt_ = tiles;
}

void FaultInjection::beforeTile() {
    if (!dieAt_) return;
    if (handled_.fetch_add(1) == *dieAt_) {
        std::fprintf(stderr, "strahl: STRAHL_DISTRIBUTED_FAULT: killing this rank (SIGKILL)\n");
        std::fflush(stderr);
        std::raise(SIGKILL);
    }
}

}  // namespace strahl::distributed
