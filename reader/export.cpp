// bhnsid-export: the reader's fields at a list of points, as a TSV table. Links libbhnsid_reader
// alone. Exit codes as the solver's: 0 done, 1 the data file could not be read, 2 bad input, 3 a bug.
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <csignal>
#include <cstring>
#include <iostream>
#include <memory>
#include <new>
#include <string>
#include <vector>

#include "bhnsid_reader.h"
#include "export_files.hpp"

namespace {

using bhnsid::exporter::BadInput;
using bhnsid::exporter::printable;

const char* const usage =
    "usage: bhnsid-export DATA.h5 --points POINTS.txt [--output FILE [--force]] [--fields f1,f2,...]\n"
    "                     [--order N] [--outside error|clamp|extrapolate]\n"
    "Interpolates the Einstein Toolkit fields of DATA.h5 (alp, betax..z, gxx..gzz, kxx..kzz, rho, press,\n"
    "eps, vel[0..2], w_lorentz; default: every field the file has) at the points of POINTS.txt (x y z per\n"
    "line, physical coordinates; '#' starts a comment; a regular file of at most 256 MiB) and writes a TSV\n"
    "table: a header line, then x y z and the fields, %.17g. --order: Lagrange points per axis (2, 4, 6, 8;\n"
    "default 4). --outside: what a point outside the grid does (default error). --output: written under a\n"
    "private temporary name in FILE's folder, fsynced, then renamed, so FILE is complete or absent; an\n"
    "existing FILE is refused unless --force, which replaces only a regular file. Exit 0, 1 if DATA.h5\n"
    "cannot be read, 2 on bad input.\n";

struct Args {
  std::string data, points, output, fields;
  int order = 4;
  int outside = BHNSID_READER_OUTSIDE_ERROR;
  bool force = false;
};

Args parse(int argc, char** argv) {
  Args a;
  bool seen_points = false, seen_output = false, seen_fields = false, seen_order = false, seen_outside = false;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const auto value = [&](const char* flag, bool& seen) -> std::string {
      if (seen) throw BadInput{std::string(flag) + " given twice"};
      seen = true;
      if (i + 1 >= argc) throw BadInput{std::string(flag) + " needs a value"};
      return argv[++i];
    };
    if (arg == "--points") {
      a.points = value("--points", seen_points);
      if (a.points.empty()) throw BadInput{"--points needs a file name"};
    } else if (arg == "--output") {
      a.output = value("--output", seen_output);
      if (a.output.empty()) throw BadInput{"--output needs a file name"};
    } else if (arg == "--force") {
      a.force = true;
    } else if (arg == "--fields") {
      a.fields = value("--fields", seen_fields);
      if (a.fields.empty()) throw BadInput{"--fields needs at least one field name"};
    } else if (arg == "--order") {
      const std::string v = value("--order", seen_order);
      if (v != "2" && v != "4" && v != "6" && v != "8")
        throw BadInput{"--order " + v + ": expected 2, 4, 6 or 8 (Lagrange points per axis)"};
      a.order = v[0] - '0';
    } else if (arg == "--outside") {
      const std::string v = value("--outside", seen_outside);
      if (v == "error") a.outside = BHNSID_READER_OUTSIDE_ERROR;
      else if (v == "clamp") a.outside = BHNSID_READER_OUTSIDE_CLAMP;
      else if (v == "extrapolate") a.outside = BHNSID_READER_OUTSIDE_EXTRAPOLATE;
      else throw BadInput{"--outside '" + v + "': expected error, clamp or extrapolate"};
    } else if (!arg.empty() && arg[0] == '-') {
      throw BadInput{"unknown option '" + arg + "'"};
    } else if (a.data.empty()) {
      if (arg.empty()) throw BadInput{"an empty DATA.h5 name"};
      a.data = arg;
    } else {
      throw BadInput{"unexpected argument '" + arg + "' (one DATA.h5 only)"};
    }
  }
  if (a.data.empty()) throw BadInput{"no DATA.h5 given"};
  if (a.points.empty()) throw BadInput{"--points POINTS.txt is required"};
  if (a.force && a.output.empty()) throw BadInput{"--force needs --output FILE"};
  return a;
}

std::vector<std::string> split(const std::string& list) {
  std::vector<std::string> out;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = list.find(',', start);
    const std::string name = list.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    if (name.empty()) throw BadInput{"--fields '" + list + "' has an empty name"};
    out.push_back(name);
    if (comma == std::string::npos) return out;
    start = comma + 1;
  }
}

/// A failed read of the data is 1; a bad request (field, order, point) is 2.
int exit_code(int status) {
  switch (status) {
    case BHNSID_READER_ERR_ARGUMENT:
    case BHNSID_READER_ERR_OUTSIDE:
    case BHNSID_READER_ERR_PUNCTURE:
    case BHNSID_READER_ERR_EOS:
      return 2;
    default:
      return 1;
  }
}

void write_table(std::FILE* f, const std::vector<std::string>& names, const std::vector<double>& x,
                 const std::vector<double>& y, const std::vector<double>& z, const std::vector<std::vector<double>>& values) {
  std::fprintf(f, "x\ty\tz");
  for (const std::string& n : names) std::fprintf(f, "\t%s", n.c_str());
  std::fprintf(f, "\n");
  for (std::size_t p = 0; p < x.size(); ++p) {
    std::fprintf(f, "%.17g\t%.17g\t%.17g", x[p], y[p], z[p]);
    for (const auto& v : values) std::fprintf(f, "\t%.17g", v[p]);
    std::fprintf(f, "\n");
  }
}

int run(const Args& a) {
  // Every refusal of the output comes before the work, so a long interpolation is not lost to it.
  if (!a.output.empty()) bhnsid::exporter::check_output(a.output, a.force, {a.data, a.points});
  const bhnsid::exporter::Points points = bhnsid::exporter::read_points(a.points);
  const std::vector<double>&x = points.x, &y = points.y, &z = points.z;
  std::vector<std::string> names;
  if (!a.fields.empty()) names = split(a.fields);
  bhnsid_reader* reader = nullptr;
  int status = bhnsid_reader_open(a.data.c_str(), &reader);
  if (status != BHNSID_READER_OK) {
    std::cerr << "bhnsid-export: " << printable(bhnsid_reader_last_error()) << "\n";
    return 1;
  }
  // Closed however run() ends: a bad request or an allocation failure throws past it.
  const std::unique_ptr<bhnsid_reader, void (*)(bhnsid_reader*)> owner(reader, bhnsid_reader_close);
  if (names.empty()) {
    std::size_t n = 0;
    bhnsid_reader_num_fields(reader, &n);
    for (std::size_t i = 0; i < n; ++i) {
      const char* name = nullptr;
      bhnsid_reader_field_name(reader, i, &name);
      names.emplace_back(name);
    }
  }
  std::vector<const char*> cnames;
  for (const std::string& n : names) cnames.push_back(n.c_str());
  std::vector<std::vector<double>> values(names.size(), std::vector<double>(x.size()));
  std::vector<double*> out;
  for (auto& v : values) out.push_back(v.data());
  bhnsid_reader_options options;
  bhnsid_reader_default_options(&options);
  options.order = a.order;
  options.out_of_grid = a.outside;
  status = bhnsid_reader_interpolate(reader, &options, x.size(), x.data(), y.data(), z.data(), names.size(), cnames.data(),
                                     out.data());
  if (status != BHNSID_READER_OK) {
    std::cerr << "bhnsid-export: " << printable(a.data + " at the points of " + a.points + ": " + bhnsid_reader_last_error())
              << "\n";
    return exit_code(status);
  }

  if (a.output.empty()) {
    write_table(stdout, names, x, y, z, values);
    if (std::fflush(stdout) != 0 || std::ferror(stdout)) throw BadInput{"cannot write the table to stdout"};
    return 0;
  }
  bhnsid::exporter::write_output(a.output, a.force, [&](std::FILE* f) { write_table(f, names, x, y, z, values); });
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  // A file-size limit (ulimit -f, a batch system's) is then a failed write, said and cleaned up, not a kill.
  std::signal(SIGXFSZ, SIG_IGN);
  for (int i = 1; i < argc; ++i)
    if (std::strcmp(argv[i], "--help") == 0 || std::strcmp(argv[i], "-h") == 0) {
      std::cout << usage;
      return 0;
    }
  try {
    return run(parse(argc, argv));
  } catch (const BadInput& e) {
    std::cerr << "bhnsid-export: " << printable(e.message) << "\n" << (argc <= 1 ? usage : "");
    return 2;
  } catch (const std::bad_alloc&) {
    std::cerr << "bhnsid-export: out of memory for the table: ask for fewer points or fields\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "bhnsid-export: internal error: " << printable(e.what()) << "\n";
    return 3;
  }
}
