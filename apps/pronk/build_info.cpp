// The commit the binary was built from (apps/pronk/git_commit.cmake writes it
// at every build, not only at configure time).
#include "commands.h"

#include "pronk_build_commit.inc"

namespace pronk::cli {

const char* buildCommit() { return PRONK_BUILD_COMMIT; }

}  // namespace pronk::cli
