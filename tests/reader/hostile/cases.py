"""The hostile-user corpus: what a careless user or a shared folder does to bhnsid-export, the Python
reader, bhnsid plot and plot_validate.py, one case a row. replay.py runs them and adds the checks
every case must pass (one line, no traceback, nothing written through a link, no PWNED, no
temporary left, no hang).

A row: id, class (a ctest test replays one class), kind (for counting), tool (export: bhnsid-export;
py: the Python reader, args PATH EXPRESSION; plot: bhnsid plot; pv: scripts/plot_validate.py), the
arguments ({w} the case's folder, {data} the fixture's data.h5, {victim} the file no case may
change, and what the setup returns), the exit code(s), a fragment the message must hold, one it
must not, a setup and an extra check.
"""

import os
import shutil
import subprocess
from collections import namedtuple

Case = namedtuple("Case", "id cls kind tool args rc text absent setup check")
CLASSES = ["export-output", "export-inputs", "export-messages", "python-contract", "plot-inputs", "plot-output",
           "names", "validate-plots"]
PWN = "x'$(touch PWNED)'y"


def case(id, cls, kind, tool, args, rc, text=None, absent=None, setup=None, check=None):
    return Case(id, cls, kind, tool, args, rc, text, absent, setup or (lambda w, v: {}), check)


# -- setups --------------------------------------------------------------------------------------

def steps(*fns):
    def run(w, v):
        out = {}
        for fn in fns:
            out.update(fn(w, dict(v, **out)) or {})
        return out
    return run


def write(name, content, key=None):
    def run(w, v):
        path = os.path.join(w, name)
        with open(path, "wb") as f:
            f.write(content if isinstance(content, bytes) else content.encode())
        return {key or "f": path}
    return run


def points(content="0 0 0\n0.3 0.2 0.1\n"):
    return write("pts.txt", content, "pts")


def sparse(name, size, key):
    def run(w, v):
        path = os.path.join(w, name)
        with open(path, "wb") as f:
            f.truncate(size)
        return {key: path}
    return run


def fifo(name, key="f"):
    def run(w, v):
        path = os.path.join(w, name)
        os.mkfifo(path)
        return {key: path}
    return run


def link(name, target="{victim}", key="l"):
    def run(w, v):
        path = os.path.join(w, name)
        os.makedirs(os.path.dirname(path), exist_ok=True)
        os.symlink(substitute_w(target, w, v), path)
        return {key: path}
    return run


def folder(name, key="d"):
    def run(w, v):
        path = os.path.join(w, name)
        os.makedirs(path, exist_ok=True)
        return {key: path}
    return run


def copy_data(name, key="d"):
    def run(w, v):
        path = os.path.join(w, name)
        shutil.copyfile(v["data"], path)
        return {key: path}
    return run


def run_copy(name="run", key="r"):
    """A run directory of its own (the files bhnsid plot reads), under `name`."""
    def run(w, v):
        path = os.path.join(w, name)
        os.makedirs(path)
        for f in ("params.yaml", "data.h5", "star_history.tsv"):
            shutil.copyfile(os.path.join(v["run"], f), os.path.join(path, f))
        return {key: path}
    return run


def in_run(name, content):
    def run(w, v):
        path = os.path.join(v["r"], name)
        os.remove(path)
        with open(path, "wb") as f:
            f.write(content if isinstance(content, bytes) else content.encode())
        return {}
    return run


def replace_in_run(name, how):
    """Removes the run's `name` and calls how(path) to put something else there."""
    def run(w, v):
        path = os.path.join(v["r"], name)
        os.remove(path)
        how(path, v)
        return {}
    return run


def h5(name, build, key="d"):
    def run(w, v):
        import h5py
        path = os.path.join(w, name)
        with h5py.File(path, "w") as f:
            build(f)
        return {key: path}
    return run


def h5_from_data(name, change, key="d"):
    """A copy of the fixture's data.h5, changed in place by change(h5py.File)."""
    def run(w, v):
        import h5py
        path = os.path.join(w, name)
        shutil.copyfile(v["data"], path)
        with h5py.File(path, "r+") as f:
            change(f)
        return {key: path}
    return run


def truncated(name, size, key="d"):
    def run(w, v):
        path = os.path.join(w, name)
        with open(v["data"], "rb") as src, open(path, "wb") as dst:
            dst.write(src.read(size))
        return {key: path}
    return run


def puncture(w, v):
    import h5py
    with h5py.File(v["data"], "r") as f:
        s = f["scalars"].attrs
        return {"bx": repr(float(s["bh_position_x"])), "by": repr(float(s["bh_position_y"]))}


def plotted(w, v):
    r = subprocess.run([v["bhnsid"], "plot", v["r"]], capture_output=True)
    assert r.returncode == 0, r.stderr
    return {}


# -- HDF5 files of the damaged kind ----------------------------------------------------------------

def header(f, shape=(5, 6, 7)):
    import numpy as np
    f.attrs["format"] = "bhnsid-data"
    f.attrs["format_version"] = np.int64(1)
    g = f.create_group("grid")
    g.attrs["shape_zyx"] = np.array(shape, dtype=float)
    g.attrs["dx"] = 0.1
    g.attrs["origin_xyz"] = np.zeros(3)
    g.attrs["symmetry"] = "none"
    return g


def no_grid(f):
    import numpy as np
    f.attrs["format"] = "bhnsid-data"
    f.attrs["format_version"] = np.int64(1)


def huge_grid(f):
    header(f, (1e6, 1e6, 1e6))
    f.create_dataset("ADMBase/alp", shape=(10 ** 6,) * 3, dtype="f8", chunks=(8, 8, 8))


def string_shape(f):
    g = header(f)
    g.attrs["shape_zyx"] = "five by six by seven"


def grid_is_dataset(f):
    import numpy as np
    no_grid(f)
    f.create_dataset("grid", data=np.zeros(3))


def bad_utf8_format(f):
    import numpy as np
    f.attrs["format"] = np.bytes_(b"bhnsid\xff\xfe-data")
    f.attrs["format_version"] = np.int64(1)


def strings_dataset(f):
    header(f)
    import numpy as np
    f.create_dataset("ADMBase/alp", data=np.full((5, 6, 7), b"a", dtype="S1"))


def nan_dataset(f):
    import numpy as np
    header(f)
    a = np.ones((5, 6, 7))
    a[2, 3, 4] = np.nan
    f.create_dataset("ADMBase/alp", data=a)


def wrong_shape(f):
    import numpy as np
    header(f)
    f.create_dataset("ADMBase/alp", data=np.ones((2, 2, 2)))


def held(size, centre=None):
    import numpy as np

    def change(f):
        for c in "xyz":
            d = f["ADMBase/beta" + c]
            d.attrs["held_region_half_size"] = np.float64(size)
            if centre is not None:
                d.attrs["held_region_centre"] = np.array([centre] * 3)
    return change


def corrupt(name, offset, key="d"):
    """The fixture's data.h5 with 64 bytes of noise at `offset` (the header and the metadata)."""
    def run(w, v):
        path = os.path.join(w, name)
        with open(v["data"], "rb") as src:
            data = bytearray(src.read())
        data[offset:offset + 64] = bytes((37 * i + 11) % 256 for i in range(64))
        with open(path, "wb") as dst:
            dst.write(data)
        return {key: path}
    return run


def corrupt_first_chunk(name, dataset, key="d"):
    """The fixture's data.h5 with 64 bytes of noise at the start of `dataset`'s first stored chunk:
    damage past the metadata, in the compressed field data, wherever the writer placed it. (Noise in
    the metadata of an HDF5 1.8-format file can crash the HDF5 library itself, in h5py as in C.)"""
    def run(w, v):
        import h5py
        with h5py.File(v["data"], "r") as f:
            offset = f[dataset].id.get_chunk_info(0).byte_offset
        return corrupt(name, offset, key)(w, v)
    return run


# -- checks ---------------------------------------------------------------------------------------

def exists(name):
    def check(w, v, rc, out, err):
        return [] if os.path.isfile(substitute_w(name, w, v)) else ["%s was not written" % name]
    return check


def unchanged(name, text):
    def check(w, v, rc, out, err):
        path = substitute_w(name, w, v)
        with open(path, "rb") as f:
            got = f.read()
        return [] if got == text.encode() else ["%s was changed" % name]
    return check


def still_link(name):
    def check(w, v, rc, out, err):
        return [] if os.path.islink(os.path.join(w, name)) else ["the link %s was replaced or removed" % name]
    return check


def no_entry(name):
    def check(w, v, rc, out, err):
        return ["%s was left behind" % name] if os.path.lexists(os.path.join(w, name)) else []
    return check


def empty_folder(name):
    def check(w, v, rc, out, err):
        left = os.listdir(os.path.join(w, name))
        return ["%s now holds %s" % (name, left)] if left else []
    return check


def pictures(folder):
    def check(w, v, rc, out, err):
        path = substitute_w(folder, w, v)
        missing = [p for p in ("equator.png", "outer_iteration.png") if not os.path.isfile(os.path.join(path, p))]
        return ["%s lacks %s" % (folder, ", ".join(missing))] if missing else []
    return check


def substitute_w(name, w, v):
    for k, val in v.items():
        name = name.replace("{%s}" % k, str(val))
    return name.replace("{w}", w)


def all_of(*checks):
    def check(w, v, rc, out, err):
        return [p for c in checks for p in (c(w, v, rc, out, err) or [])]
    return check


REPORT = """{"axis_rescaled": {"x": [0, 0.1, 0.2, 0.3], "hamiltonian": [[1, 2, 3, 4], [1.1, 2.1, 3.1, 4.1]]},
 "axis_region": ["away", "puncture", "away", "surface"],
 "levels": [{"parameters": {"grid.n": 32}}, {"parameters": {"grid.n": 64}}],
 "equations": {"hamiltonian": {"verdict": "converges", "order_l2": [2.01]}}}
"""


GOOD = "Reader(P).interpolate([0.1], [0.2], [0.3], ['alp', 'gxx', 'rho'])"
TABLE = "{w}/out.tsv"

CASES = [
    # -- bhnsid-export: the output file ------------------------------------------------------------
    case("export_link_at_partial", "export-output", "symlink", "export", ["{data}", "--points", "{pts}", "--output", TABLE],
         0, setup=steps(points(), link("out.tsv.partial")), check=all_of(exists(TABLE), still_link("out.tsv.partial"))),
    case("export_users_partial_kept", "export-output", "existing-file", "export",
         ["{data}", "--points", "{pts}", "--output", TABLE], 0, setup=steps(points(), write("out.tsv.partial", "mine\n")),
         check=all_of(exists(TABLE), unchanged("{w}/out.tsv.partial", "mine\n"))),
    case("export_link_at_output", "export-output", "symlink", "export", ["{data}", "--points", "{pts}", "--output", TABLE],
         2, "exists", setup=steps(points(), link("out.tsv")), check=still_link("out.tsv")),
    case("export_link_at_output_force", "export-output", "symlink", "export",
         ["{data}", "--points", "{pts}", "--output", TABLE, "--force"], 2, "symbolic link",
         setup=steps(points(), link("out.tsv")), check=still_link("out.tsv")),
    case("export_dangling_link_at_output", "export-output", "symlink", "export",
         ["{data}", "--points", "{pts}", "--output", TABLE], 2, "exists",
         setup=steps(points(), link("out.tsv", "{w}/nowhere"))),
    case("export_users_output_kept", "export-output", "existing-file", "export",
         ["{data}", "--points", "{pts}", "--output", TABLE], 2, "pass --force",
         setup=steps(points(), write("out.tsv", "mine\n")), check=unchanged(TABLE, "mine\n")),
    case("export_force_replaces_regular", "export-output", "existing-file", "export",
         ["{data}", "--points", "{pts}", "--output", TABLE, "--force"], 0,
         setup=steps(points(), write("out.tsv", "old\n")), check=exists(TABLE)),
    case("export_output_is_folder", "export-output", "folder", "export",
         ["{data}", "--points", "{pts}", "--output", "{d}", "--force"], 2, "a folder", setup=steps(points(), folder("out"))),
    case("export_output_is_fifo", "export-output", "fifo-device", "export",
         ["{data}", "--points", "{pts}", "--output", "{f}", "--force"], 2, "a FIFO", setup=steps(points(), fifo("out.tsv"))),
    case("export_output_is_the_data", "export-output", "existing-file", "export",
         ["{d}", "--points", "{pts}", "--output", "{d}", "--force"], 2, "is the input file",
         setup=steps(points(), copy_data("data.h5"))),
    case("export_output_is_the_points", "export-output", "existing-file", "export",
         ["{data}", "--points", "{pts}", "--output", "{pts}", "--force"], 2, "is the input file", setup=points()),
    case("export_output_folder_missing", "export-output", "folder", "export",
         ["{data}", "--points", "{pts}", "--output", "{w}/no/such/out.tsv"], 2, "does not exist", setup=points()),
    case("export_output_trailing_slash", "export-output", "folder", "export",
         ["{data}", "--points", "{pts}", "--output", "{w}/out/"], 2, "names a folder", setup=points()),
    # Through a link, not /dev/full itself: run against a tool that renames over its output, the
    # case must not replace a device of the system.
    case("export_output_link_to_device", "export-output", "fifo-device", "export",
         ["{data}", "--points", "{pts}", "--output", "{l}", "--force"], 2, "a symbolic link",
         setup=steps(points(), link("out.tsv", "/dev/full")), check=still_link("out.tsv")),
    case("export_output_empty", "export-output", "option", "export", ["{data}", "--points", "{pts}", "--output", ""], 2,
         "--output needs a file name", setup=points()),
    # -- bhnsid-export: inputs ---------------------------------------------------------------------
    case("export_fifo_data", "export-inputs", "fifo-device", "export", ["{f}", "--points", "{pts}"], 1, "is a FIFO",
         setup=steps(points(), fifo("data.h5"))),
    case("export_fifo_points", "export-inputs", "fifo-device", "export", ["{data}", "--points", "{f}"], 2, "is a FIFO",
         setup=fifo("pts.txt")),
    case("export_dev_zero_points", "export-inputs", "endless-input", "export", ["{data}", "--points", "/dev/zero"], 2,
         "/dev/zero: the points file is a device"),
    case("export_link_to_dev_zero_points", "export-inputs", "endless-input", "export", ["{data}", "--points", "{l}"], 2,
         "is a device", setup=link("pts.txt", "/dev/zero")),
    case("export_dev_null_data", "export-inputs", "fifo-device", "export", ["/dev/null", "--points", "{pts}"], 1,
         "is a device", setup=points()),
    case("export_folder_data", "export-inputs", "folder", "export", ["{w}", "--points", "{pts}"], 1, "directory",
         setup=points()),
    case("export_folder_points", "export-inputs", "folder", "export", ["{data}", "--points", "{w}"], 2, "a folder"),
    case("export_long_line", "export-inputs", "endless-input", "export", ["{data}", "--points", "{pts}"], 2,
         ":1: a line of more than 4096 characters", setup=points("0 " * 5000 + "\n")),
    case("export_huge_points_file", "export-inputs", "endless-input", "export", ["{data}", "--points", "{pts}"], 2,
         "larger than 256 MiB", setup=sparse("pts.txt", 300 << 20, "pts")),
    case("export_nul_in_points", "export-inputs", "number", "export", ["{data}", "--points", "{pts}"], 2,
         ":2: ", setup=points(b"0 0 0\n0 0\x00 0\n")),
    case("export_binary_points", "export-inputs", "number", "export", ["{data}", "--points", "{pts}"], 2, "pts.txt:1:",
         setup=points(bytes(range(256)) * 4)),
    case("export_text_data", "export-inputs", "damaged-hdf5", "export", ["{f}", "--points", "{pts}"], 1,
         "not an HDF5 file", setup=steps(points(), write("data.h5", "hello\n"))),
    case("export_empty_data", "export-inputs", "damaged-hdf5", "export", ["{f}", "--points", "{pts}"], 1,
         "not an HDF5 file", setup=steps(points(), write("data.h5", b""))),
    case("export_truncated_data", "export-inputs", "damaged-hdf5", "export", ["{d}", "--points", "{pts}"], 1, "data.h5",
         setup=steps(points(), truncated("data.h5", 30000))),
    case("export_no_grid", "export-inputs", "damaged-hdf5", "export", ["{d}", "--points", "{pts}"], 1, "no group /grid",
         setup=steps(points(), h5("data.h5", no_grid))),
    case("export_huge_dimensions", "export-inputs", "damaged-hdf5", "export",
         ["{d}", "--points", "{pts}", "--fields", "alp"], 1, "out of memory: /ADMBase/alp holds 1000000 x",
         setup=steps(points(), h5("data.h5", huge_grid))),
    case("export_corrupt_header", "export-inputs", "damaged-hdf5", "export", ["{d}", "--points", "{pts}"], (0, 1),
         setup=steps(points(), corrupt("data.h5", 200))),
    case("export_corrupt_metadata", "export-inputs", "damaged-hdf5", "export", ["{d}", "--points", "{pts}"], (0, 1),
         setup=steps(points(), corrupt("data.h5", 4000))),
    case("export_data_through_link", "export-inputs", "symlink", "export", ["{l}", "--points", "{pts}"], 0,
         setup=steps(points(), link("data.h5", "{data}"))),
    # -- bhnsid-export: messages and options -------------------------------------------------------
    case("export_extrapolate_100", "export-messages", "extrapolation", "export",
         ["{data}", "--points", "{pts}", "--outside", "extrapolate", "--fields", "gxx"], 2, "too far outside the grid",
         absent="at the puncture", setup=points("100 0 0\n")),
    case("export_extrapolate_1e300", "export-messages", "extrapolation", "export",
         ["{data}", "--points", "{pts}", "--outside", "extrapolate", "--fields", "kxx"], 2, "too far outside the grid",
         setup=points("1e300 0 0\n")),
    case("export_extrapolate_near", "export-messages", "extrapolation", "export",
         ["{data}", "--points", "{pts}", "--outside", "extrapolate"], 0, setup=points("4.8 0 0\n")),
    case("export_at_the_puncture", "export-messages", "number", "export", ["{data}", "--points", "{pts}"], 2,
         "at the puncture", setup=steps(puncture, lambda w, v: points("%s %s 0\n" % (v["bx"], v["by"]))(w, v))),
    case("export_outside", "export-messages", "number", "export", ["{data}", "--points", "{pts}"], 2,
         "outside the grid", setup=points("0 0 0\n99 0 0\n")),
    case("export_held_half_size_1e300", "export-messages", "number", "export",
         ["{d}", "--points", "{pts}", "--fields", "betax"], 1, "covers the whole grid",
         setup=steps(points(), h5_from_data("data.h5", held(1e300)))),
    case("export_held_half_size_1e6", "export-messages", "number", "export",
         ["{d}", "--points", "{pts}", "--fields", "betax"], 1, "covers the whole grid",
         setup=steps(points(), h5_from_data("data.h5", held(1e6)))),
    case("export_held_far_centre", "export-messages", "number", "export",
         ["{d}", "--points", "{pts}", "--fields", "betax"], 0, setup=steps(points(), h5_from_data("data.h5", held(1e300, 1e308)))),
    case("export_nan_point", "export-messages", "number", "export", ["{data}", "--points", "{pts}"], 2,
         "pts.txt:1: 'nan' is not a number", setup=points("nan 0 0\n")),
    case("export_inf_point", "export-messages", "number", "export", ["{data}", "--points", "{pts}"], 2,
         "'-inf' is not a number", setup=points("0 -inf 0\n")),
    case("export_hex_point", "export-messages", "number", "export", ["{data}", "--points", "{pts}"], 2,
         "'0x10' is not a number", setup=points("0x10 0 0\n")),
    case("export_overflow_point", "export-messages", "number", "export", ["{data}", "--points", "{pts}"], 2,
         "'1e999' overflows", setup=points("0 0 1e999\n")),
    case("export_two_numbers", "export-messages", "number", "export", ["{data}", "--points", "{pts}"], 2,
         ":2: expected three numbers", setup=points("0 0 0\n1 2\n")),
    case("export_order_5", "export-messages", "option", "export", ["{data}", "--points", "{pts}", "--order", "5"], 2,
         "--order 5: expected 2, 4, 6 or 8", setup=points()),
    case("export_order_huge", "export-messages", "option", "export", ["{data}", "--points", "{pts}", "--order", "1e999"],
         2, "--order", setup=points()),
    case("export_order_negative", "export-messages", "option", "export", ["{data}", "--points", "{pts}", "--order", "-4"],
         2, "--order", setup=points()),
    case("export_outside_bogus", "export-messages", "option", "export",
         ["{data}", "--points", "{pts}", "--outside", "$(touch PWNED)"], 2, "expected error, clamp or extrapolate",
         setup=points()),
    case("export_points_twice", "export-messages", "option", "export", ["{data}", "--points", "{pts}", "--points", "{pts}"],
         2, "--points given twice", setup=points()),
    case("export_fields_empty", "export-messages", "option", "export", ["{data}", "--points", "{pts}", "--fields", ""], 2,
         "--fields", setup=points()),
    case("export_fields_empty_name", "export-messages", "option", "export",
         ["{data}", "--points", "{pts}", "--fields", "alp,,rho"], 2, "empty name", setup=points()),
    case("export_field_with_newline", "export-messages", "option", "export",
         ["{data}", "--points", "{pts}", "--fields", "alp\nrm -rf ~"], 2, "unknown field 'alp\\x0arm", setup=points()),
    case("export_unknown_option", "export-messages", "option", "export", ["{data}", "--points", "{pts}", "--bogus"], 2,
         "unknown option '--bogus'", setup=points()),
    case("export_force_alone", "export-messages", "option", "export", ["{data}", "--points", "{pts}", "--force"], 2,
         "--force needs --output", setup=points()),
    case("export_two_data_files", "export-messages", "option", "export", ["{data}", "{data}", "--points", "{pts}"], 2,
         "one DATA.h5 only", setup=points()),
    case("export_missing_points_value", "export-messages", "option", "export", ["{data}", "--points"], 2,
         "--points needs a value"),
    case("export_missing_data", "export-messages", "option", "export", ["{w}/none.h5", "--points", "{pts}"], 1,
         "no such file", setup=points()),
    # -- names: no shell, any character --------------------------------------------------------------
    case("export_quote_in_data_name", "names", "name", "export", ["{d}", "--points", "{pts}"], 0,
         setup=steps(points(), copy_data("Bob's data.h5"))),
    case("export_command_in_data_name", "names", "name", "export", ["{d}", "--points", "{pts}"], 0,
         setup=steps(points(), copy_data(PWN + ".h5"))),
    case("export_newline_in_data_name", "names", "name", "export", ["{d}", "--points", "{pts}"], 0,
         setup=steps(points(), copy_data("a\nb.h5"))),
    case("export_command_in_output_name", "names", "name", "export",
         ["{data}", "--points", "{pts}", "--output", "{w}/" + PWN + ".tsv"], 0, setup=points(),
         check=exists("{w}/" + PWN + ".tsv")),
    case("export_newline_in_output_name", "names", "name", "export",
         ["{data}", "--points", "{pts}", "--output", "{w}/a\nb.tsv"], 0, setup=points(), check=exists("{w}/a\nb.tsv")),
    case("export_newline_in_missing_name", "names", "name", "export", ["{w}/no\nsuch.h5", "--points", "{pts}"], 1,
         "no\\x0asuch.h5", setup=points()),
    case("python_command_in_name", "names", "name", "py", ["{d}", GOOD], 0, setup=copy_data(PWN + ".h5")),
    case("python_newline_in_name", "names", "name", "py", ["{d}", GOOD], 0, setup=copy_data("a\nb'c.h5")),
    case("plot_quote_in_run_name", "names", "name", "plot", ["{r}"], 0, setup=run_copy("Bob's runs"),
         check=pictures("{r}/plots")),
    case("plot_command_in_run_name", "names", "name", "plot", ["{r}"], 0, setup=run_copy(PWN),
         check=pictures("{r}/plots")),
    case("plot_newline_in_run_name", "names", "name", "plot", ["{r}"], 0, setup=run_copy("a\nb"),
         check=pictures("{r}/plots")),
    case("plot_command_in_output_name", "names", "name", "plot", ["{r}", "--output", "{w}/" + PWN + " plots"], 0,
         setup=run_copy(), check=pictures("{w}/" + PWN + " plots")),
    case("validate_plots_command_in_folder_name", "names", "name", "pv", ["{d}/validate.json", "{d}"], 0,
         setup=steps(folder(PWN), write(PWN + "/validate.json", REPORT))),
    # -- the Python reader: ReaderError and nothing else ------------------------------------------------
    case("python_text_file", "python-contract", "damaged-hdf5", "py", ["{f}", "Reader(P)"], 1, "ReaderError 2:",
         setup=write("data.h5", "hello\n")),
    case("python_empty_file", "python-contract", "damaged-hdf5", "py", ["{f}", "Reader(P)"], 1, "ReaderError 2:",
         setup=write("data.h5", b"")),
    case("python_truncated", "python-contract", "damaged-hdf5", "py", ["{d}", GOOD], 1, "ReaderError 2:",
         setup=truncated("data.h5", 30000)),
    case("python_no_grid", "python-contract", "damaged-hdf5", "py", ["{d}", "Reader(P)"], 1, "ReaderError 3:",
         setup=h5("data.h5", no_grid)),
    case("python_grid_is_a_dataset", "python-contract", "damaged-hdf5", "py", ["{d}", "Reader(P)"], 1, "ReaderError 3:",
         setup=h5("data.h5", grid_is_dataset)),
    case("python_shape_is_text", "python-contract", "damaged-hdf5", "py", ["{d}", "Reader(P)"], 1, "ReaderError 3:",
         setup=h5("data.h5", string_shape)),
    case("python_format_not_utf8", "python-contract", "damaged-hdf5", "py", ["{d}", "Reader(P)"], 1, "ReaderError 3:",
         setup=h5("data.h5", bad_utf8_format)),
    case("python_strings_dataset", "python-contract", "damaged-hdf5", "py",
         ["{d}", "Reader(P).interpolate([0.1], [0.1], [0.1], ['alp'])"], 1, "ReaderError 3:",
         setup=h5("data.h5", strings_dataset)),
    case("python_nan_dataset", "python-contract", "number", "py",
         ["{d}", "Reader(P).interpolate([0.1], [0.1], [0.1], ['alp'])"], 1, "non-finite", setup=h5("data.h5", nan_dataset)),
    case("python_wrong_shape", "python-contract", "damaged-hdf5", "py",
         ["{d}", "Reader(P).interpolate([0.1], [0.1], [0.1], ['alp'])"], 1, "not /grid@shape_zyx",
         setup=h5("data.h5", wrong_shape)),
    case("python_huge_dimensions", "python-contract", "damaged-hdf5", "py",
         ["{d}", "Reader(P).interpolate([0.1], [0.1], [0.1], ['alp'])"], 1, "ReaderError 9: out of memory",
         setup=h5("data.h5", huge_grid)),
    case("python_fifo", "python-contract", "fifo-device", "py", ["{f}", "Reader(P)"], 1, "ReaderError 2:",
         setup=fifo("data.h5")),
    case("python_dev_zero", "python-contract", "endless-input", "py", ["/dev/zero", "Reader(P)"], 1,
         "is a device, not a regular file"),
    case("python_folder", "python-contract", "folder", "py", ["{w}", "Reader(P)"], 1, "ReaderError 2:"),
    case("python_missing", "python-contract", "damaged-hdf5", "py", ["{w}/none.h5", "Reader(P)"], 1,
         "ReaderError 2: no such file"),
    case("python_path_none", "python-contract", "option", "py", ["{data}", "Reader(None)"], 1, "ReaderError 1:"),
    case("python_held_1e300", "python-contract", "number", "py",
         ["{d}", "Reader(P).interpolate([0.1], [0.1], [0.1], ['betax'])"], 1, "covers the whole grid",
         setup=h5_from_data("data.h5", held(1e300))),
    case("python_held_far", "python-contract", "number", "py",
         ["{d}", "Reader(P).interpolate([0.1], [0.1], [0.1], ['betax'])"], (0, 1),
         setup=h5_from_data("data.h5", held(1e308, -1e308))),
    case("python_extrapolate_100", "python-contract", "extrapolation", "py",
         ["{data}", "Reader(P).interpolate([100.0], [0.0], [0.0], ['gxx'], outside='extrapolate')"], 1,
         "ReaderError 5:", absent="at the puncture"),
    case("python_extrapolate_1e300", "python-contract", "extrapolation", "py",
         ["{data}", "Reader(P).interpolate([1e300], [0.0], [0.0], ['kxx'], outside='extrapolate')"], 1, "ReaderError 5:"),
    case("python_nan_point", "python-contract", "number", "py",
         ["{data}", "Reader(P).interpolate([np.nan], [0], [0], ['alp'])"], 1, "ReaderError 1:"),
    case("python_order_float", "python-contract", "option", "py",
         ["{data}", "Reader(P).interpolate([0.1], [0], [0], ['alp'], order=4.5)"], 1, "ReaderError 1:"),
    case("python_order_text", "python-contract", "option", "py",
         ["{data}", "Reader(P).interpolate([0.1], [0], [0], ['alp'], order='4')"], 1, "ReaderError 1:"),
    case("python_outside_list", "python-contract", "option", "py",
         ["{data}", "Reader(P).interpolate([0.1], [0], [0], ['alp'], outside=['clamp'])"], 1, "ReaderError 1:"),
    case("python_field_number", "python-contract", "option", "py",
         ["{data}", "Reader(P).interpolate([0.1], [0], [0], [1])"], 1, "ReaderError 1:"),
    case("python_coordinates_text", "python-contract", "option", "py",
         ["{data}", "Reader(P).interpolate('abc', [0], [0], ['alp'])"], 1, "ReaderError 1:"),
    case("python_attribute_name_number", "python-contract", "option", "py",
         ["{data}", "Reader(P).string_attribute(7, 'status')"], 1, "ReaderError 1:"),
    case("python_corrupt_header", "python-contract", "damaged-hdf5", "py", ["{d}", GOOD], (0, 1),
         setup=corrupt("data.h5", 200)),
    case("python_corrupt_metadata", "python-contract", "damaged-hdf5", "py", ["{d}", GOOD], (0, 1),
         setup=corrupt("data.h5", 4000)),
    case("python_corrupt_deeper", "python-contract", "damaged-hdf5", "py", ["{d}", GOOD], (0, 1),
         setup=corrupt_first_chunk("data.h5", "ADMBase/alp")),
    # -- bhnsid plot: inputs -----------------------------------------------------------------------
    case("plot_text_data", "plot-inputs", "damaged-hdf5", "plot", ["{r}"], 2, "data.h5: is not an HDF5 file",
         setup=steps(run_copy(), in_run("data.h5", "hello\n"))),
    case("plot_truncated_data", "plot-inputs", "damaged-hdf5", "plot", ["{r}"], 2, "truncated",
         setup=steps(run_copy(), replace_in_run("data.h5", lambda p, v: truncated(p, 30000)("/", v)))),
    case("plot_gridless_data", "plot-inputs", "damaged-hdf5", "plot", ["{r}"], 2, "has no /grid",
         setup=steps(run_copy(), replace_in_run("data.h5", lambda p, v: h5(p, no_grid)("/", v)))),
    case("plot_huge_grid", "plot-inputs", "damaged-hdf5", "plot", ["{r}"], 2, "more than a picture can show",
         setup=steps(run_copy(), replace_in_run("data.h5", lambda p, v: h5(p, huge_grid)("/", v)))),
    case("plot_wrong_shape", "plot-inputs", "damaged-hdf5", "plot", ["{r}"], 2, "not a dataset of the grid's shape",
         setup=steps(run_copy(), replace_in_run("data.h5", lambda p, v: h5(p, wrong_shape)("/", v)))),
    case("plot_fifo_data", "plot-inputs", "fifo-device", "plot", ["{r}"], 2, "is a FIFO",
         setup=steps(run_copy(), replace_in_run("data.h5", lambda p, v: os.mkfifo(p)))),
    case("plot_missing_data", "plot-inputs", "damaged-hdf5", "plot", ["{r}"], 2, "data.h5: is missing",
         setup=steps(run_copy(), replace_in_run("data.h5", lambda p, v: None))),
    # No picture: the folders plot made for them go again, the ones above the output included.
    case("plot_nothing_into_new_folders", "plot-inputs", "folder", "plot", ["{r}", "--output", "{w}/new/deep/pics/"], 2,
         "data.h5: is missing", setup=steps(run_copy(), replace_in_run("data.h5", lambda p, v: None)),
         check=no_entry("new")),
    # equator.png is drawn before the history fails: a failed script's pictures are not kept.
    case("plot_garbled_history", "plot-inputs", "damaged-hdf5", "plot", ["{r}"], 2, "star_history.tsv:3:",
         setup=steps(run_copy(), in_run("star_history.tsv", "# iteration sigma omega_hat bernoulli_constant change\n"
                                                          "1 2 3 4 5\n1 2 three 4 5\n")),
         check=lambda w, v, rc, out, err: ["plots/ was left"] if os.path.lexists(os.path.join(v["r"], "plots")) else []),
    case("plot_binary_history", "plot-inputs", "damaged-hdf5", "plot", ["{r}"], 2, "star_history.tsv",
         setup=steps(run_copy(), in_run("star_history.tsv", bytes(range(256)) * 8))),
    case("plot_headerless_history", "plot-inputs", "damaged-hdf5", "plot", ["{r}"], 2, "star_history.tsv:1:",
         setup=steps(run_copy(), in_run("star_history.tsv", "1 2 3\n"))),
    case("plot_empty_history", "plot-inputs", "damaged-hdf5", "plot", ["{r}"], 2, "star_history.tsv",
         setup=steps(run_copy(), in_run("star_history.tsv", ""))),
    case("plot_nan_history", "plot-inputs", "number", "plot", ["{r}"], 2, "finite numbers",
         setup=steps(run_copy(), in_run("star_history.tsv", "# iteration sigma omega_hat bernoulli_constant change\n"
                                                          "1 nan 3 4 5\n"))),
    case("plot_fifo_history", "plot-inputs", "fifo-device", "plot", ["{r}"], 2, "is a FIFO",
         setup=steps(run_copy(), replace_in_run("star_history.tsv", lambda p, v: os.mkfifo(p)))),
    case("plot_dev_zero_history", "plot-inputs", "endless-input", "plot", ["{r}"], 2, "is a device",
         setup=steps(run_copy(), replace_in_run("star_history.tsv", lambda p, v: os.symlink("/dev/zero", p)))),
    case("plot_fifo_params", "plot-inputs", "fifo-device", "plot", ["{r}"], 2, "not a run directory",
         setup=steps(run_copy(), replace_in_run("params.yaml", lambda p, v: os.mkfifo(p)))),
    case("plot_not_a_run", "plot-inputs", "folder", "plot", ["{w}"], 2, "not a run directory"),
    case("plot_empty_run_name", "plot-inputs", "option", "plot", [""], 2, "expected a run directory"),
    # -- bhnsid plot: the pictures ---------------------------------------------------------------------
    case("plot_link_at_picture", "plot-output", "symlink", "plot", ["{r}"], 2, "equator.png: is a symbolic link",
         setup=steps(run_copy(), link("run/plots/equator.png")), check=still_link("run/plots/equator.png")),
    case("plot_users_picture_kept", "plot-output", "existing-file", "plot", ["{r}"], 2, "bhnsid plot did not write it",
         setup=steps(run_copy(), folder("run/plots"), write("run/plots/equator.png", "my picture\n")),
         check=unchanged("{w}/run/plots/equator.png", "my picture\n")),
    case("plot_users_picture_in_output", "plot-output", "existing-file", "plot", ["{r}", "--output", "{d}"], 2,
         "bhnsid plot did not write it", setup=steps(run_copy(), folder("mine"), write("mine/outer_iteration.png", "x\n")),
         check=unchanged("{w}/mine/outer_iteration.png", "x\n")),
    case("plot_plots_folder_is_link", "plot-output", "symlink", "plot", ["{r}"], 2, "is a symbolic link",
         setup=steps(run_copy(), folder("elsewhere"), link("run/plots", "{w}/elsewhere")), check=empty_folder("elsewhere")),
    case("plot_plots_is_a_file", "plot-output", "folder", "plot", ["{r}"], 2, "is a regular file",
         setup=steps(run_copy(), write("run/plots", "not a folder\n"))),
    case("plot_record_is_link", "plot-output", "symlink", "plot", ["{r}"], 2, ".bhnsid-plots: is a symbolic link",
         setup=steps(run_copy(), link("run/plots/.bhnsid-plots"))),
    case("plot_record_is_foreign", "plot-output", "existing-file", "plot", ["{r}"], 2, "is not bhnsid plot's record",
         setup=steps(run_copy(), folder("run/plots"), write("run/plots/.bhnsid-plots", "my notes\n"))),
    case("plot_replaces_its_own", "plot-output", "existing-file", "plot", ["{r}"], 0,
         setup=steps(run_copy(), plotted), check=pictures("{r}/plots")),
    case("plot_keeps_other_files", "plot-output", "existing-file", "plot", ["{r}"], 0,
         setup=steps(run_copy(), folder("run/plots"), write("run/plots/notes.txt", "mine\n")),
         check=all_of(pictures("{r}/plots"), unchanged("{w}/run/plots/notes.txt", "mine\n"))),
    case("plot_bad_input_writes_nothing", "plot-output", "damaged-hdf5", "plot", ["{r}"], 2, "not an HDF5 file",
         setup=steps(run_copy(), in_run("data.h5", "hello\n")),
         check=lambda w, v, rc, out, err: ["plots/ was left"] if os.path.lexists(os.path.join(v["r"], "plots")) else []),
    # -- plot_validate.py --------------------------------------------------------------------------
    case("validate_plots_garbage_json", "validate-plots", "damaged-hdf5", "pv", ["{f}", "{w}"], 2, "is not JSON",
         setup=write("validate.json", "{\"x\":\n")),
    case("validate_plots_wrong_structure", "validate-plots", "damaged-hdf5", "pv", ["{f}", "{w}"], 2, "malformed",
         setup=write("validate.json", "{\"axis_rescaled\": {\"x\": [1]}, \"levels\": [], "
                                      "\"equations\": {\"hamiltonian\": {\"verdict\": 3}}}")),
    case("validate_plots_not_a_report", "validate-plots", "damaged-hdf5", "pv", ["{f}", "{w}"], 2,
         "not a report of bhnsid validate", setup=write("validate.json", "[1, 2, 3]")),
    case("validate_plots_fifo", "validate-plots", "fifo-device", "pv", ["{f}", "{w}"], 2, "not a regular file",
         setup=fifo("validate.json")),
    case("validate_plots_link_at_old_temporary", "validate-plots", "symlink", "pv", ["{f}", "{w}"], 0,
         setup=steps(write("validate.json", REPORT), link("residual_hamiltonian.png.tmp.png")),
         check=still_link("residual_hamiltonian.png.tmp.png")),
]
