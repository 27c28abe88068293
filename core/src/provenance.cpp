#include <unistd.h>

#include <ctime>

#include "bhnsid/core/build_info.hpp"
#include "bhnsid/core/run.hpp"

namespace bhnsid::core {

Provenance provenance(const std::string& command_line) {
  Provenance p;
  p.version = build_version();
  p.git_revision = build_git_revision();
  p.build_type = build_type();
  p.compiler = build_compiler();
  char host[256] = {};
  if (::gethostname(host, sizeof host - 1) == 0) p.host = host;
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  char date[32];
  std::strftime(date, sizeof date, "%Y-%m-%dT%H:%M:%SZ", &utc);
  p.date = date;
  p.command_line = command_line;
  return p;
}

}  // namespace bhnsid::core
