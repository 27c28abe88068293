// The C boundary: every exception becomes a status and a thread-local message.
#include <cstring>
#include <memory>
#include <new>
#include <string>
#include <vector>

#include "bhnsid_reader.h"
#include "data_file.hpp"
#include "fields.hpp"
#include "lagrange.hpp"

using bhnsid::reader::DataFile;
using bhnsid::reader::Error;

struct bhnsid_reader {
  std::unique_ptr<DataFile> file;
  std::vector<std::string> fields;  // available_fields(), fixed at open
};

namespace {

thread_local std::string last_error;
thread_local bool last_error_lost = false;  // the message itself could not be stored (no memory)

void set_error(const char* message) noexcept {
  try {
    last_error = message;
    last_error_lost = false;
  } catch (...) {
    last_error_lost = true;
  }
}

template <class Body>
int guarded(Body&& body) noexcept {
  try {
    body();
    return BHNSID_READER_OK;
  } catch (const Error& e) {
    set_error(e.what());
    return e.code();
  } catch (const std::bad_alloc&) {
    set_error("out of memory");
  } catch (const std::exception& e) {
    try {
      set_error((std::string("internal error: ") + e.what()).c_str());
    } catch (...) {
      set_error("internal error");
    }
  } catch (...) {
    set_error("internal error: an unknown exception");
  }
  return BHNSID_READER_ERR_INTERNAL;
}

void require(const void* p, const char* what) {
  if (!p) throw Error(BHNSID_READER_ERR_ARGUMENT, std::string(what) + " is NULL");
}

const DataFile& file_of(const bhnsid_reader* r) {
  require(r, "the reader handle");
  return *r->file;
}

void check_index(std::size_t index, std::size_t count, const char* what) {
  if (index >= count)
    throw Error(BHNSID_READER_ERR_ARGUMENT, std::string(what) + " index " + std::to_string(index) + " is out of range (" +
                                                std::to_string(count) + " of them)");
}

}  // namespace

extern "C" {

const char* bhnsid_reader_last_error(void) { return last_error_lost ? "out of memory" : last_error.c_str(); }

void bhnsid_reader_default_options(bhnsid_reader_options* options) {
  if (!options) return;
  options->order = 4;
  options->out_of_grid = BHNSID_READER_OUTSIDE_ERROR;
}

int bhnsid_reader_open(const char* path, bhnsid_reader** out) {
  if (out) *out = nullptr;
  return guarded([&] {
    require(out, "the output handle pointer");
    require(path, "the path");
    auto r = std::make_unique<bhnsid_reader>();
    r->file = std::make_unique<DataFile>(path);
    r->fields = bhnsid::reader::available_fields(*r->file);
    *out = r.release();
  });
}

void bhnsid_reader_close(bhnsid_reader* reader) {
  // Destructors do not throw; a failing H5Fclose is reported nowhere (nothing can be done).
  delete reader;
}

int bhnsid_reader_grid_info(const bhnsid_reader* reader, bhnsid_reader_grid* grid) {
  return guarded([&] {
    const bhnsid::reader::Grid& g = file_of(reader).grid();
    require(grid, "the grid output");
    grid->nx = g.nx;
    grid->ny = g.ny;
    grid->nz = g.nz;
    grid->dx = g.dx;
    grid->equatorial = g.equatorial ? 1 : 0;
    const int first[3] = {0, 0, g.kmin()}, last[3] = {g.nx - 1, g.ny - 1, g.nz - 1};
    for (int a = 0; a < 3; ++a) {
      grid->origin[a] = g.origin[static_cast<std::size_t>(a)];
      grid->lower[a] = g.origin[static_cast<std::size_t>(a)] + g.dx * first[a];
      grid->upper[a] = g.origin[static_cast<std::size_t>(a)] + g.dx * last[a];
    }
  });
}

int bhnsid_reader_num_datasets(const bhnsid_reader* reader, size_t* count) {
  return guarded([&] {
    const DataFile& f = file_of(reader);
    require(count, "the count output");
    *count = f.datasets().size();
  });
}

int bhnsid_reader_dataset_name(const bhnsid_reader* reader, size_t index, const char** name) {
  return guarded([&] {
    const DataFile& f = file_of(reader);
    require(name, "the name output");
    check_index(index, f.datasets().size(), "dataset");
    *name = f.datasets()[index].c_str();
  });
}

int bhnsid_reader_num_fields(const bhnsid_reader* reader, size_t* count) {
  return guarded([&] {
    file_of(reader);
    require(count, "the count output");
    *count = reader->fields.size();
  });
}

int bhnsid_reader_field_name(const bhnsid_reader* reader, size_t index, const char** name) {
  return guarded([&] {
    file_of(reader);
    require(name, "the name output");
    check_index(index, reader->fields.size(), "field");
    *name = reader->fields[index].c_str();
  });
}

int bhnsid_reader_num_scalars(const bhnsid_reader* reader, size_t* count) {
  return guarded([&] {
    const DataFile& f = file_of(reader);
    require(count, "the count output");
    *count = f.scalar_names().size();
  });
}

int bhnsid_reader_scalar_name(const bhnsid_reader* reader, size_t index, const char** name) {
  return guarded([&] {
    const DataFile& f = file_of(reader);
    require(name, "the name output");
    check_index(index, f.scalar_names().size(), "scalar");
    *name = f.scalar_names()[index].c_str();
  });
}

int bhnsid_reader_scalar(const bhnsid_reader* reader, const char* name, double* value) {
  return guarded([&] {
    const DataFile& f = file_of(reader);
    require(name, "the scalar's name");
    require(value, "the value output");
    const std::optional<double> v = f.scalar(name);
    if (!v) throw Error(BHNSID_READER_ERR_NOT_FOUND, std::string("no scalar '") + name + "' in " + f.path());
    *value = *v;
  });
}

int bhnsid_reader_string_attribute(bhnsid_reader* reader, const char* object, const char* name, const char** value) {
  return guarded([&] {
    const DataFile& f = file_of(reader);
    require(object, "the object path");
    require(name, "the attribute name");
    require(value, "the value output");
    *value = f.string_attribute(object, name).c_str();
  });
}

int bhnsid_reader_numeric_attribute(bhnsid_reader* reader, const char* object, const char* name, double* values,
                                    size_t capacity, size_t* count) {
  return guarded([&] {
    const DataFile& f = file_of(reader);
    require(object, "the object path");
    require(name, "the attribute name");
    require(count, "the count output");
    if (capacity > 0) require(values, "the values output");
    const std::vector<double> v = f.numeric_attribute(object, name);
    *count = v.size();
    for (std::size_t i = 0; i < v.size() && i < capacity; ++i) values[i] = v[i];
  });
}

int bhnsid_reader_interpolate(bhnsid_reader* reader, const bhnsid_reader_options* options, size_t npts,
                              const double* x, const double* y, const double* z, size_t nfields,
                              const char* const* fields, double* const* out) {
  return guarded([&] {
    const DataFile& f = file_of(reader);
    bhnsid::reader::Options o;
    if (options) {
      o.order = options->order;
      o.out_of_grid = options->out_of_grid;
    }
    bhnsid::reader::check_options(f.grid(), o);
    if (nfields > 0) {
      require(fields, "the field names");
      require(out, "the output arrays");
    }
    std::vector<std::string> names;
    for (std::size_t i = 0; i < nfields; ++i) {
      if (!fields[i]) throw Error(BHNSID_READER_ERR_ARGUMENT, "field name " + std::to_string(i) + " is NULL");
      if (npts > 0 && !out[i]) throw Error(BHNSID_READER_ERR_ARGUMENT, "output array " + std::to_string(i) + " is NULL");
      names.emplace_back(fields[i]);
    }
    if (npts > 0) {
      require(x, "x");
      require(y, "y");
      require(z, "z");
    }
    const bhnsid::reader::Request request(f, names);
    // All points first, into a buffer: a failing point leaves the caller's arrays untouched.
    std::vector<double> values(npts * nfields);
    for (std::size_t p = 0; p < npts; ++p) {
      const bhnsid::reader::Stencil s = bhnsid::reader::stencil_at(f.grid(), o, x[p], y[p], z[p], p);
      request.evaluate(s, p, values.data() + p * nfields);
    }
    for (std::size_t p = 0; p < npts; ++p)
      for (std::size_t i = 0; i < nfields; ++i) out[i][p] = values[p * nfields + i];
  });
}

}  // extern "C"
