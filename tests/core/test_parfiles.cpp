// Every example parameter file in parfiles/ is valid with the plugins that ship: `bhnsid check`
// accepts it (exit 0). The physics of each is tested by its plugin's suite; this keeps a new or
// edited example from rotting unnoticed.
#include <catch2/catch.hpp>

#include <filesystem>
#include <string>

#include "process.hpp"

using namespace bhnsid::test;
namespace fs = std::filesystem;

TEST_CASE("core.parfiles.every_example_passes_check", "[core]") {
  int count = 0;
  for (const auto& entry : fs::directory_iterator(source_dir() / "parfiles")) {
    if (entry.path().extension() != ".yaml") continue;
    ++count;
    const ProcessResult r = run_bhnsid({"check", entry.path().string()});
    INFO(entry.path().filename().string() << ":\n" << r.out << r.err);
    CHECK(r.exit_code == 0);
  }
  CHECK(count >= 6);
}
