#pragma once
// The two commands of the CLI; each returns the process exit status and throws
// strahl::Error for anything the user must fix.

#include "options.h"

namespace strahl::app {

int runRender(const Options& options);
int runInfo(const Options& options);

}  // namespace strahl::app
