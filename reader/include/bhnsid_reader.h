/* bhnsid_reader.h: read a bhnsid data.h5 (docs/output-format.md, format_version 1) and
 * interpolate its Einstein Toolkit fields at arbitrary physical points.
 *
 * C99 / C++ API of libbhnsid_reader. Every function returns a status (BHNSID_READER_OK = 0 or an
 * error code below); after a non-zero return, bhnsid_reader_last_error() says why, in words. The
 * library never prints, aborts or exits. Interpolation calls on one handle may run concurrently
 * from several threads; open and close may not race with other calls on the same handle.
 * Semantics (puncture, excision fill, EOS, out-of-grid policy): reader/README.md. */
#ifndef BHNSID_READER_H
#define BHNSID_READER_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

#if defined(__GNUC__)
#define BHNSID_READER_API __attribute__((visibility("default")))
#else
#define BHNSID_READER_API
#endif

enum {
  BHNSID_READER_OK = 0,
  BHNSID_READER_ERR_ARGUMENT = 1, /* a null pointer, an unknown field name, a bad option */
  BHNSID_READER_ERR_IO = 2,       /* the file is missing, unreadable or not HDF5 */
  BHNSID_READER_ERR_FORMAT = 3,   /* not a bhnsid data.h5, another format_version, a malformed dataset */
  BHNSID_READER_ERR_NOT_FOUND = 4, /* the attribute, scalar or dataset is not in the file */
  BHNSID_READER_ERR_OUTSIDE = 5,   /* a point outside the grid (with BHNSID_READER_OUTSIDE_ERROR) */
  BHNSID_READER_ERR_PUNCTURE = 6,  /* a point at the puncture, where the metric is infinite */
  BHNSID_READER_ERR_EOS = 7,       /* press or eps asked of a file whose EOS has no formulas */
  BHNSID_READER_ERR_VALUE = 8,     /* a result that would not be finite (e.g. |v| >= 1) */
  BHNSID_READER_ERR_INTERNAL = 9   /* out of memory or a bug: the message says which */
};

/* What a point outside the grid's box does (the box: origin_xyz to origin_xyz + dx (shape - 1), and
 * z in [-z_max, z_max] under equatorial symmetry). */
enum {
  BHNSID_READER_OUTSIDE_ERROR = 0,      /* the call fails with BHNSID_READER_ERR_OUTSIDE (default) */
  BHNSID_READER_OUTSIDE_CLAMP = 1,      /* the point is moved to the nearest point of the box */
  BHNSID_READER_OUTSIDE_EXTRAPOLATE = 2 /* the edge stencil's polynomial is evaluated outside */
};

typedef struct bhnsid_reader bhnsid_reader;

typedef struct {
  int order;       /* points per axis of the Lagrange stencil: 2, 4 (default), 6 or 8; error O(dx^order) */
  int out_of_grid; /* BHNSID_READER_OUTSIDE_ERROR (default), _CLAMP or _EXTRAPOLATE */
} bhnsid_reader_options;

typedef struct {
  int nx, ny, nz;      /* stored points per axis (nz: z >= 0 only under equatorial symmetry) */
  double dx;           /* physical spacing */
  double origin[3];    /* physical coordinates of point (0, 0, 0) */
  int equatorial;      /* 1: only z >= 0 stored, the rest by each field's parity */
  double lower[3];     /* the box where points are inside the grid (physical) */
  double upper[3];
} bhnsid_reader_grid;

/* The message of the last failed call in this thread ("" if none failed yet). Valid until the next
 * failing call in this thread. */
BHNSID_READER_API const char* bhnsid_reader_last_error(void);

/* Fills the defaults: order 4, BHNSID_READER_OUTSIDE_ERROR. */
BHNSID_READER_API void bhnsid_reader_default_options(bhnsid_reader_options* options);

/* Opens `path`, checks format == "bhnsid-data" and format_version == 1, reads the grid, the scalars
 * and the EOS. Datasets are read lazily, on first use. *out is NULL on failure. */
BHNSID_READER_API int bhnsid_reader_open(const char* path, bhnsid_reader** out);
/* Closes the file and frees everything; NULL is allowed. Not concurrently with other calls on it. */
BHNSID_READER_API void bhnsid_reader_close(bhnsid_reader* reader);

BHNSID_READER_API int bhnsid_reader_grid_info(const bhnsid_reader* reader, bhnsid_reader_grid* grid);

/* The 3-D datasets of the file as paths ("/ADMBase/alp", "/HydroBase/vel[0]", "/variables/chi"),
 * sorted. Names stay valid until close. */
BHNSID_READER_API int bhnsid_reader_num_datasets(const bhnsid_reader* reader, size_t* count);
BHNSID_READER_API int bhnsid_reader_dataset_name(const bhnsid_reader* reader, size_t index, const char** name);

/* The fields bhnsid_reader_interpolate() computes for this file, in the order of the reader's
 * table (alp, betax..z, gxx..gzz, kxx..kzz, rho, press, eps, vel[0..2], w_lorentz): those the
 * file holds or implies. Absent betax/kxx count as present (zero); press and eps need /eos@model;
 * the fluid needs HydroBase. */
BHNSID_READER_API int bhnsid_reader_num_fields(const bhnsid_reader* reader, size_t* count);
BHNSID_READER_API int bhnsid_reader_field_name(const bhnsid_reader* reader, size_t index, const char** name);

/* The scalars: the numeric attributes of /scalars (physical unless the name ends in _hat). */
BHNSID_READER_API int bhnsid_reader_num_scalars(const bhnsid_reader* reader, size_t* count);
BHNSID_READER_API int bhnsid_reader_scalar_name(const bhnsid_reader* reader, size_t index, const char** name);
BHNSID_READER_API int bhnsid_reader_scalar(const bhnsid_reader* reader, const char* name, double* value);

/* A string attribute, e.g. ("/", "status"), ("/eos", "description"), ("/parameters", "resolved").
 * The string stays valid until close. */
BHNSID_READER_API int bhnsid_reader_string_attribute(bhnsid_reader* reader, const char* object, const char* name,
                                                     const char** value);
/* A numeric attribute (integer or double, scalar or array): *count receives its length; at most
 * `capacity` values are written to `values` (pass capacity 0 to ask the length). */
BHNSID_READER_API int bhnsid_reader_numeric_attribute(bhnsid_reader* reader, const char* object, const char* name,
                                                      double* values, size_t capacity, size_t* count);

/* Interpolates `nfields` fields at `npts` physical points (x[p], y[p], z[p]): out[f][p] receives
 * field fields[f] at point p. A field is an ETK name of the table above, or a dataset path
 * ("/variables/chi", "/ADMBase/gxx") for the stored values alone (mirrored and, for a held region,
 * filled, but without the puncture's pole or the EOS). `options` NULL: the defaults. On an error no
 * output is written and the message names the first point or field at fault. Thread-safe. */
BHNSID_READER_API int bhnsid_reader_interpolate(bhnsid_reader* reader, const bhnsid_reader_options* options,
                                                size_t npts, const double* x, const double* y, const double* z,
                                                size_t nfields, const char* const* fields, double* const* out);

#ifdef __cplusplus
}
#endif

#endif /* BHNSID_READER_H */
