#pragma once
// Facts fixed when bhnsid was built; the git revision is refreshed on every build.
namespace bhnsid::core {
const char* build_version();
const char* build_git_revision();
const char* build_type();
const char* build_compiler();
}  // namespace bhnsid::core
