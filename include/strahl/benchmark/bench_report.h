#pragma once
// What `strahl bench` prints and writes: a table, CSV or JSON rows, and a
// log-log plot (SVG) of the cost per camera ray against the triangle count for
// the naive tracer and Embree, with the fitted growth of each.

#include <cstdio>
#include <filesystem>
#include <span>
#include <string>

#include "strahl/benchmark/bench_suite.h"

namespace strahl {

// The growth fits over the generated ladder (models differ in more than size,
// so they are plotted but not fitted).
struct BenchFits {
    PowerFit naive, embree;  // ns per ray ∝ triangles^slope
    LogFit embreeLog;        // Embree ns per ray = a + b log10(triangles)
};
BenchFits fitBench(std::span<const BenchRow> rows);

void printBenchTable(std::FILE* out, std::span<const BenchRow> rows, const BenchFits& fits);

// The rows as CSV (one header line, one line per scene) or JSON (options,
// rows, fits), by the file's extension: .csv or .json. Written to a temporary
// name and renamed; throws strahl::Error naming the file if it cannot be
// written, or if the extension is neither.
void writeBenchResults(const std::filesystem::path& file, std::span<const BenchRow> rows,
                       const BenchFits& fits, const BenchOptions& options);

// Whether writeBenchResults / writeBenchPlot could write `file`: the right
// extension (the same check and message as theirs) and an existing folder. A
// run calls these to refuse bad outputs before anything is measured.
void checkBenchResultsFile(const std::filesystem::path& file);
void checkBenchPlotFile(const std::filesystem::path& file);

// The plot as SVG (the extension must be .svg), written the same way.
void writeBenchPlot(const std::filesystem::path& file, std::span<const BenchRow> rows,
                    const BenchFits& fits);

}  // namespace strahl
