// `strahl render --distributed` started without mpirun: one clear error and no
// output, whichever way strahl was built — with MPI it is a job of one process
// (at least 2 are needed), without MPI the flag is refused with the way to get
// it. The distributed renders themselves are tested in tests/distributed/
// (built only with STRAHL_MPI=ON).

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "app/cli_runner.h"
#include "test_support.h"

namespace strahl {
namespace {

namespace fs = std::filesystem;

TEST(DistributedFlag, WithoutMpirunOrWithoutMpiIsOneClearError) {
    const fs::path dir = test::scratchDir("distributed-flag");
    const std::string scene = (test::sourceDir() / "scenes/regression/cornell_direct.json").string();
    const test::RunResult r = test::runStrahl("render " + scene + " --width 8 --height 8 -q -o " +
                                              (dir / "a.exr").string() + " --distributed");
    const std::string oneProcess =
        "strahl: error: --distributed needs at least 2 MPI processes (rank 0 schedules, the "
        "others render), got 1: start it with mpirun -np N, N >= 2 (docs/distributed.md)\n";
    const std::string noMpi =
        "strahl: error: --distributed: this strahl was built without MPI; configure with "
        "-DSTRAHL_MPI=ON (docs/distributed.md)\n";
    if (r.status == 2) {
        EXPECT_EQ(r.err, oneProcess);
    } else {
        EXPECT_EQ(r.status, 1);
        EXPECT_EQ(r.err, noMpi);
    }
    EXPECT_TRUE(fs::is_empty(dir)) << "an output was written";
}

}  // namespace
}  // namespace strahl
