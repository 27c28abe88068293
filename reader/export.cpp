// bhnsid-export: the reader's fields at a list of points, as a TSV table. Links libbhnsid_reader
// alone. Exit codes as the solver's: 0 done, 1 the data file could not be read, 2 bad input.
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "bhnsid_reader.h"

namespace {

const char* const usage =
    "usage: bhnsid-export DATA.h5 --points POINTS.txt [--output FILE [--force]] [--fields f1,f2,...]\n"
    "                     [--order N] [--outside error|clamp|extrapolate]\n"
    "Interpolates the Einstein Toolkit fields of DATA.h5 (alp, betax..z, gxx..gzz, kxx..kzz, rho, press,\n"
    "eps, vel[0..2], w_lorentz; default: every field the file has) at the points of POINTS.txt (x y z per\n"
    "line, physical coordinates; '#' starts a comment) and writes a TSV table: a header line, then x y z\n"
    "and the fields, %.17g. --order: Lagrange points per axis (2, 4, 6, 8; default 4). --outside: what a\n"
    "point outside the grid does (default error). --output: written as FILE.partial then renamed, so FILE\n"
    "is complete or absent; an existing FILE is refused unless --force. Exit 0, 1 if DATA.h5 cannot be\n"
    "read, 2 on bad input.\n";

struct BadInput {
  std::string message;
};

struct Args {
  std::string data, points, output, fields;
  int order = 4;
  int outside = BHNSID_READER_OUTSIDE_ERROR;
  bool force = false;
};

Args parse(int argc, char** argv) {
  Args a;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const auto value = [&](const char* flag) -> std::string {
      if (i + 1 >= argc) throw BadInput{std::string(flag) + " needs a value"};
      return argv[++i];
    };
    if (arg == "--points") {
      a.points = value("--points");
    } else if (arg == "--output") {
      a.output = value("--output");
    } else if (arg == "--force") {
      a.force = true;
    } else if (arg == "--fields") {
      a.fields = value("--fields");
      if (a.fields.empty()) throw BadInput{"--fields needs at least one field name"};
    } else if (arg == "--order") {
      const std::string v = value("--order");
      char* end = nullptr;
      errno = 0;
      const long n = std::strtol(v.c_str(), &end, 10);
      if (v.empty() || *end != '\0' || errno != 0 || n < 1 || n > 64)
        throw BadInput{"--order '" + v + "' is not a small positive integer"};
      a.order = static_cast<int>(n);
    } else if (arg == "--outside") {
      const std::string v = value("--outside");
      if (v == "error") a.outside = BHNSID_READER_OUTSIDE_ERROR;
      else if (v == "clamp") a.outside = BHNSID_READER_OUTSIDE_CLAMP;
      else if (v == "extrapolate") a.outside = BHNSID_READER_OUTSIDE_EXTRAPOLATE;
      else throw BadInput{"--outside '" + v + "': expected error, clamp or extrapolate"};
    } else if (!arg.empty() && arg[0] == '-') {
      throw BadInput{"unknown option '" + arg + "'"};
    } else if (a.data.empty()) {
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

void read_points(const std::string& path, std::vector<double>& x, std::vector<double>& y, std::vector<double>& z) {
  std::ifstream in(path);
  if (!in) throw BadInput{"cannot read the points file " + path};
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    const std::size_t hash = line.find('#');
    if (hash != std::string::npos) line.resize(hash);
    std::istringstream s(line);
    std::vector<double> v;
    std::string word;
    while (s >> word) {
      char* end = nullptr;
      const double d = std::strtod(word.c_str(), &end);
      if (*end != '\0') throw BadInput{path + ":" + std::to_string(number) + ": '" + word + "' is not a number"};
      v.push_back(d);
    }
    if (v.empty()) continue;
    if (v.size() != 3)
      throw BadInput{path + ":" + std::to_string(number) + ": expected three numbers x y z, found " +
                     std::to_string(v.size())};
    x.push_back(v[0]);
    y.push_back(v[1]);
    z.push_back(v[2]);
  }
  if (in.bad()) throw BadInput{"error while reading " + path};
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

/// FILE.partial, flushed to disk, then moved to FILE: a reader of FILE never sees half a table, and
/// a failure leaves FILE as it was. Without --force, link() makes the final step fail if FILE
/// appeared meanwhile (rename would replace it), so a file this run did not write is never lost.
void write_file(const Args& a, const std::vector<std::string>& names, const std::vector<double>& x,
                const std::vector<double>& y, const std::vector<double>& z, const std::vector<std::vector<double>>& values) {
  if (!a.force && access(a.output.c_str(), F_OK) == 0)
    throw BadInput{a.output + " exists; pass --force to replace it"};
  const std::string partial = a.output + ".partial";
  std::FILE* f = std::fopen(partial.c_str(), "w");
  if (!f) throw BadInput{"cannot write " + partial + ": " + std::strerror(errno)};
  write_table(f, names, x, y, z, values);
  bool ok = std::fflush(f) == 0 && !std::ferror(f) && fsync(fileno(f)) == 0;
  const int saved = errno;
  ok = std::fclose(f) == 0 && ok;
  if (!ok) {
    std::remove(partial.c_str());
    throw BadInput{"cannot write " + partial + ": " + std::strerror(saved)};
  }
  if (a.force) {
    if (std::rename(partial.c_str(), a.output.c_str()) != 0) {
      const int e = errno;
      std::remove(partial.c_str());
      throw BadInput{"cannot rename " + partial + " to " + a.output + ": " + std::strerror(e)};
    }
    return;
  }
  if (link(partial.c_str(), a.output.c_str()) != 0) {
    const int e = errno;
    std::remove(partial.c_str());
    throw BadInput{e == EEXIST ? a.output + " exists; pass --force to replace it"
                               : "cannot create " + a.output + ": " + std::strerror(e)};
  }
  std::remove(partial.c_str());
}

int run(const Args& a) {
  std::vector<double> x, y, z;
  read_points(a.points, x, y, z);
  bhnsid_reader* reader = nullptr;
  int status = bhnsid_reader_open(a.data.c_str(), &reader);
  if (status != BHNSID_READER_OK) {
    std::cerr << "bhnsid-export: " << bhnsid_reader_last_error() << "\n";
    return 1;
  }
  std::vector<std::string> names;
  if (!a.fields.empty()) {
    names = split(a.fields);
  } else {
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
    std::cerr << "bhnsid-export: " << a.data << " at the points of " << a.points << ": " << bhnsid_reader_last_error()
              << "\n";
    bhnsid_reader_close(reader);
    return exit_code(status);
  }
  bhnsid_reader_close(reader);

  if (a.output.empty()) {
    write_table(stdout, names, x, y, z, values);
    if (std::fflush(stdout) != 0 || std::ferror(stdout)) throw BadInput{"cannot write the table to stdout"};
    return 0;
  }
  write_file(a, names, x, y, z, values);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  for (int i = 1; i < argc; ++i)
    if (std::strcmp(argv[i], "--help") == 0 || std::strcmp(argv[i], "-h") == 0) {
      std::cout << usage;
      return 0;
    }
  try {
    return run(parse(argc, argv));
  } catch (const BadInput& e) {
    std::cerr << "bhnsid-export: " << e.message << "\n" << (argc <= 1 ? usage : "");
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "bhnsid-export: " << e.what() << "\n";
    return 1;
  }
}
