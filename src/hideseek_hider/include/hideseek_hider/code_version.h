// The version of the code this library was built from (cmake/code_version.cmake): the git commit,
// with "-dirty-<hash of the changes>" for uncommitted changes, or "unknown".
#pragma once

namespace hideseek_hider {
const char* codeVersion();
}  // namespace hideseek_hider
