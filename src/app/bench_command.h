#pragma once
// `strahl bench`: the benchmark suite from the command line (the measuring is
// in the benchmark module; this file turns options into a run and a report).

#include <optional>
#include <string>

namespace CLI {
class App;
}

namespace strahl::app {

struct BenchCommandOptions {
    std::string ladder = "1e2,1e3,1e4,1e5,1e6,1e7";  // comma-separated sizes, or "none"
    std::string models;                              // comma-separated, "all", "none"; "" = all if found
    std::string data;                                // "" = $STRAHL_DATA, else ../shared/data
    int resolution = 512;
    int threads = 0;
    int repeats = 3;
    double naiveBudget = 2e9;
    bool noRaster = false;
    std::string out, plot;
    bool quiet = false;
    // Path tracing (path_bench.h): comma-separated scene names, or "none".
    std::string path = "cornell,sponza";
    int pathSpp = 16;
    std::string scenes;  // "" = ./scenes, else the source tree of the executable
};

// Adds the `bench` subcommand and its options to `app`.
CLI::App* addBenchCommand(CLI::App& app, BenchCommandOptions& options);

// Runs it; returns the exit status, throws strahl::Error for bad input.
int runBench(const BenchCommandOptions& options);

}  // namespace strahl::app
