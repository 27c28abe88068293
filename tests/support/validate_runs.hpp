#pragma once
// `bhnsid validate` as a child process, and its validate.json, for the tests that judge orders.
#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>
#include <vector>

#include "process.hpp"

namespace bhnsid::test {

struct Validated {
  int exit_code = -1;
  std::string output;
  nlohmann::json report;
  double order(const std::string& eq) const { return report["equations"][eq]["order_l2"].back().get<double>(); }
  std::string verdict(const std::string& eq) const { return report["equations"][eq]["verdict"].get<std::string>(); }
};

/// `bhnsid validate parfile --output dir/vN --no-plots --set s ... extra...`; the report is empty
/// when validate wrote none.
inline Validated validate(const TempDir& dir, const std::string& parfile, const std::vector<std::string>& sets,
                          const std::vector<std::string>& extra = {}) {
  static int counter = 0;
  std::string name = "v";
  name.append(std::to_string(counter++));  // not "v" + ...: GCC 12 warns falsely (-Wrestrict) on that
  const auto out = dir.path() / name;
  std::vector<std::string> args{"validate", parfile, "--output", out.string(), "--no-plots"};
  for (const std::string& s : sets) args.insert(args.end(), {"--set", s});
  args.insert(args.end(), extra.begin(), extra.end());
  const ProcessResult p = run_bhnsid(args);
  Validated v;
  v.exit_code = p.exit_code;
  v.output = p.out + p.err;
  if (std::filesystem::exists(out / "validate.json")) v.report = nlohmann::json::parse(read_file(out / "validate.json"));
  return v;
}

}  // namespace bhnsid::test
