// strahl's entry point: parse the command line, run the command, and turn every
// failure into one message on stderr and a non-zero exit status.

#include <cstdio>
#include <exception>
#include <new>

#include "commands.h"
#include "options.h"
#include "strahl/core/error.h"
#include "strahl/distributed/distributed.h"

int main(int argc, char** argv) {
    using namespace strahl::app;
    Options options;
    if (const auto code = parseOptions(argc, argv, options)) return *code;
    try {
        switch (options.command) {
            case Command::Render:
                // Every rank runs the same render; the workers print nothing.
                if (options.distributed)
                    return strahl::distributed::run([&] {
                        if (strahl::distributed::role() == strahl::distributed::Role::Worker)
                            options.quiet = true;
                        return runRender(options);
                    });
                return runRender(options);
            case Command::Convert: return runConvert(options);
            case Command::Bench: return runBench(options.bench);
            case Command::Assemble: return runAssemble(options.assemble);
            case Command::Merge: return runMerge(options.merge);
            case Command::Denoise: return runDenoise(options.denoise);
            default: return runInfo(options);
        }
    } catch (const strahl::Error& e) {
        std::fprintf(stderr, "strahl: error: %s\n", e.what());
    } catch (const std::bad_alloc&) {
        std::fprintf(stderr, "strahl: error: out of memory\n");
    } catch (const std::exception& e) {
        std::fprintf(stderr, "strahl: error: %s\n", e.what());
    }
    return 1;
}
