#pragma once
// The render, info and convert commands of the CLI (render_command.cpp,
// info_command.cpp, convert_command.cpp; merge, assemble and bench have their
// own headers); each
// returns the process exit status and throws strahl::Error for anything the
// user must fix.

#include "options.h"

namespace strahl::app {

int runRender(const Options& options);
int runInfo(const Options& options);
int runConvert(const Options& options);

}  // namespace strahl::app
