/* example.c: the reader's C API in a few lines. Build against an installed reader:
 *   cc example.c $(pkg-config --cflags --libs bhnsid_reader) -o example && ./example runs/quickstart/data.h5
 * Prints alp, gxx and rho at three points along the x axis between the grid's centre and its edge. */
#include <stdio.h>

#include "bhnsid_reader.h"

int main(int argc, char** argv) {
  if (argc != 2) {
    fprintf(stderr, "usage: %s DATA.h5\n", argv[0]);
    return 2;
  }
  bhnsid_reader* reader = NULL;
  if (bhnsid_reader_open(argv[1], &reader) != BHNSID_READER_OK) {
    fprintf(stderr, "example: %s\n", bhnsid_reader_last_error());
    return 1;
  }
  bhnsid_reader_grid grid;
  bhnsid_reader_grid_info(reader, &grid);

  enum { npts = 3 };
  double x[npts], y[npts], z[npts];
  for (int p = 0; p < npts; ++p) {
    /* Off the grid points and off the axis, so every value is interpolated. */
    x[p] = 0.5 * (grid.lower[0] + grid.upper[0]) + (p + 0.37) * 0.25 * (grid.upper[0] - grid.lower[0]) / npts;
    y[p] = 0.5 * (grid.lower[1] + grid.upper[1]) + 0.13 * grid.dx;
    z[p] = 0.21 * grid.dx;
  }
  const char* fields[3] = {"alp", "gxx", "rho"};
  double alp[npts], gxx[npts], rho[npts];
  double* out[3] = {alp, gxx, rho};
  const int status = bhnsid_reader_interpolate(reader, NULL, npts, x, y, z, 3, fields, out);
  if (status != BHNSID_READER_OK) {
    fprintf(stderr, "example: %s\n", bhnsid_reader_last_error());
    bhnsid_reader_close(reader);
    return 1;
  }
  printf("x y z alp gxx rho\n");
  for (int p = 0; p < npts; ++p) printf("%.17g %.17g %.17g %.17g %.17g %.17g\n", x[p], y[p], z[p], alp[p], gxx[p], rho[p]);
  bhnsid_reader_close(reader);
  return 0;
}
