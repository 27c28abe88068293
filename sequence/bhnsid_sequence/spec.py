"""The sequence file (sequence/README.md): a base parameter file, mu_bn, the xhat_A list, the
rho_max list or range, the target rest masses and the grid configurations of the error model.
The whole file is checked before anything runs; bad input is one SpecError naming the file, the
key and what was expected (exit 2)."""
import math
import os
import re
import stat
from dataclasses import dataclass, field
from pathlib import Path
from typing import Dict, List

from .safe_io import InputError, read_regular
from .spec_yaml import YamlError, load, where

# The paper's Table III: the grid configurations per mu_bn, the finest (the tabulated one) first.
PAPER_GRIDS = {
    1.0: [(256, 0.015), (128, 0.03), (160, 0.015)],
    3.0: [(256, 0.015), (128, 0.03), (160, 0.015)],
    10.0: [(256, 0.01), (128, 0.02), (160, 0.014375)],
}

# Bounds that keep a mistyped file from scheduling millions of runs: the paper's sequences have
# 5 xhat_A, 10 rho_max, 4 targets and 3 grids (150 runs). A sequence file is a few hundred bytes.
MAX_FILE_BYTES = 64 * 1024
MAX_VALUES = 200
MAX_GRIDS = 8
MAX_CONFIGURATIONS = 5000
MAX_THREADS = 1024
# What the sequence sets in every run itself; a `set:` of one of these would be overridden.
OWN_KEYS = {"grid.n": "sequence.grids", "grid.dx": "sequence.grids", "puncture.mass_ratio": "sequence.mass_ratio",
            "star.x_a": "sequence.x_a", "star.rho_max": "sequence.rho_max",
            "run.threads": "sequence.threads"}
_SET_KEY = re.compile(r"[A-Za-z0-9_]+(\.[A-Za-z0-9_]+)+")


class SpecError(InputError):
    pass


def key(v: float) -> str:
    """The name of a value in run directories and table keys: six significant digits where they
    give the value back exactly (0.08397, 0.015: the names a user reads), else every digit
    (repr), so that two values never share a name however close they are."""
    short = f"{v:.6g}"
    return short if float(short) == v else repr(v)


@dataclass(frozen=True)
class Grid:
    n: int
    dx: float

    @property
    def rc(self) -> float:
        return self.n * self.dx / 2

    @property
    def name(self) -> str:
        return f"n{self.n}_dx{key(self.dx)}"


@dataclass
class Spec:
    file: Path
    base: Path
    mass_ratio: float
    x_a: List[float]
    rho_max: List[float]
    targets: List[float]
    grids: List[Grid]
    overrides: Dict[str, str] = field(default_factory=dict)
    threads: int = 1


def show(value) -> str:
    """A value as the error line shows it, as YAML would write it: short, on one line."""
    if isinstance(value, bool) or value is None:
        return {True: "true", False: "false", None: "nothing (null)"}[value]
    text = repr(value)
    return text if len(text) <= 60 else text[:57] + "..."


def _is_number(v) -> bool:
    return isinstance(v, (int, float)) and not isinstance(v, bool)


class _Checker:
    def __init__(self, file: Path):
        self.file = file

    def fail(self, path, expected, value) -> SpecError:
        return SpecError(f"{self.file}: {where(path)}: expected {expected}, got {show(value)}")

    def number(self, path, v, expected="a finite number"):
        if not _is_number(v) or not math.isfinite(v):
            raise self.fail(path, expected, v)
        return float(v)

    def integer(self, path, v, lo, hi, expected):
        if not isinstance(v, int) or isinstance(v, bool) or not lo <= v <= hi:
            raise self.fail(path, expected, v)
        return v

    def mapping(self, path, v, known, required, expected):
        if not isinstance(v, dict):
            raise self.fail(path, expected, v)
        for k in v:
            if k not in known:
                raise SpecError(f"{self.file}: {where(path + [k])}: unknown key; expected one of "
                                f"{', '.join(sorted(known))}")
        for k in required:
            if k not in v:
                raise SpecError(f"{self.file}: {where(path + [k])}: missing")
        return v

    def numbers(self, path, value, inside, test):
        """A list of distinct numbers, or {from: A, to: B, count: N}, each passing TEST (INSIDE
        says what it expects)."""
        if isinstance(value, dict):
            self.mapping(path, value, {"from", "to", "count"}, ("from", "to", "count"),
                         "a list of numbers or {from: A, to: B, count: N}")
            start = self.number(path + ["from"], value["from"])
            stop = self.number(path + ["to"], value["to"])
            count = self.integer(path + ["count"], value["count"], 2, MAX_VALUES,
                                 f"an integer from 2 to {MAX_VALUES}")
            if not stop > start:
                raise self.fail(path + ["to"], f"a number above from = {key(start)}", stop)
            value = [start + (stop - start) * i / (count - 1) for i in range(count)]
        if not isinstance(value, list) or not value:
            raise self.fail(path, "a non-empty list of numbers or {from: A, to: B, count: N}", value)
        if len(value) > MAX_VALUES:
            raise SpecError(f"{self.file}: {where(path)}: {len(value)} values; at most {MAX_VALUES}")
        out = []
        for i, v in enumerate(value):
            x = self.number(path + [i], v, f"a finite number {inside}")
            if not test(x):
                raise self.fail(path + [i], f"a number {inside}", v)
            out.append(x)
        seen = {}
        for i, x in enumerate(out):
            if x in seen:
                raise SpecError(f"{self.file}: {where(path + [i])}: {key(x)} is listed twice (also at [{seen[x]}])")
            seen[x] = i
        return out

    def grids(self, path, value):
        if not isinstance(value, list) or not value:
            raise self.fail(path, "a list of {n: N, dx: DX}, finest first", value)
        if len(value) > MAX_GRIDS:
            raise SpecError(f"{self.file}: {where(path)}: {len(value)} grids; at most {MAX_GRIDS}")
        grids = []
        for i, g in enumerate(value):
            self.mapping(path + [i], g, {"n", "dx"}, ("n", "dx"), "{n: N, dx: DX}")
            n = g["n"]
            if not isinstance(n, int) or isinstance(n, bool) or n < 4 or n % 2:
                raise self.fail(path + [i, "n"], "an even integer >= 4", n)
            dx = self.number(path + [i, "dx"], g["dx"], "a finite number > 0")
            if not dx > 0:
                raise self.fail(path + [i, "dx"], "a finite number > 0", g["dx"])
            if Grid(n, dx) in grids:
                raise SpecError(f"{self.file}: {where(path + [i])}: the grid n = {n}, dx = {key(dx)} is listed twice")
            grids.append(Grid(n, dx))
        return grids

    def overrides(self, path, value):
        if value is None:
            return {}
        if not isinstance(value, dict):
            raise self.fail(path, "a mapping section.key: value", value)
        out = {}
        for k, v in value.items():
            if not _SET_KEY.fullmatch(k):
                raise SpecError(f"{self.file}: {where(path)}: {show(k)}: expected a parameter name section.key")
            if k in OWN_KEYS:
                raise SpecError(f"{self.file}: {where(path + [k])}: set by the sequence itself from {OWN_KEYS[k]}")
            out[k] = self.override_value(path + [k], v)
        return out

    def override_value(self, path, v):
        """The text of --set key=TEXT: as the core reads a parameter file's value."""
        if isinstance(v, bool):
            return "true" if v else "false"
        if _is_number(v):
            return repr(self.number(path, v)) if isinstance(v, float) else str(v)
        if isinstance(v, str):
            if any(ord(c) < 32 or ord(c) == 127 for c in v):
                raise self.fail(path, "a value without control characters", v)
            return v
        if isinstance(v, list) and v and all(_is_number(x) for x in v):
            return "[" + ",".join(self.override_value(path + [i], x) for i, x in enumerate(v)) + "]"
        raise self.fail(path, "a number, true/false, a word or a list of numbers", v)


def read_spec(path) -> Spec:
    path = Path(path)
    try:
        data = read_regular(path, MAX_FILE_BYTES, follow=True, what="a sequence file")
    except InputError as e:
        raise SpecError(str(e))
    except (OSError, ValueError) as e:
        raise SpecError(f"{path}: cannot read the sequence file: {getattr(e, 'strerror', None) or e}")
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as e:
        raise SpecError(f"{path}: not UTF-8 text (byte {e.start} is {data[e.start]:#04x})")
    try:
        doc = load(text)
    except YamlError as e:
        raise SpecError(f"{path}:{e}")
    c = _Checker(path)
    if not isinstance(doc, dict) or not isinstance(doc.get("sequence"), dict):
        raise SpecError(f"{path}: expected a mapping with a section 'sequence'")
    for k in doc:
        if k != "sequence":
            raise SpecError(f"{path}: {k}: unknown section; expected only 'sequence'")
    s = c.mapping(["sequence"], doc["sequence"],
                  {"base", "mass_ratio", "x_a", "rho_max", "targets", "grids", "set", "threads"},
                  ("base", "mass_ratio", "x_a", "rho_max", "targets"), "a mapping")
    base = _base(c, path, s["base"])
    mu = c.number(["sequence", "mass_ratio"], s["mass_ratio"], "a finite number > 0")
    if not mu > 0:
        raise c.fail(["sequence", "mass_ratio"], "a finite number > 0", s["mass_ratio"])
    if s.get("grids") is None:
        if mu not in PAPER_GRIDS:
            raise SpecError(f"{path}: sequence.grids: missing, and the paper gives none for mass_ratio = {key(mu)} "
                            f"(only {', '.join(key(k) for k in PAPER_GRIDS)})")
        grids = [Grid(n, dx) for n, dx in PAPER_GRIDS[mu]]
    else:
        grids = c.grids(["sequence", "grids"], s["grids"])
    x_a = c.numbers(["sequence", "x_a"], s["x_a"], "in [-1, 1]", lambda v: -1 <= v <= 1)
    rho_max = sorted(c.numbers(["sequence", "rho_max"], s["rho_max"], "> 0", lambda v: v > 0))
    targets = c.numbers(["sequence", "targets"], s["targets"], "in (0, 1]", lambda v: 0 < v <= 1)
    count = len(grids) * len(x_a) * len(rho_max)
    if count > MAX_CONFIGURATIONS:
        raise SpecError(f"{path}: sequence: {len(grids)} grids x {len(x_a)} x_a x {len(rho_max)} rho_max = {count} "
                        f"runs; at most {MAX_CONFIGURATIONS}")
    threads = c.integer(["sequence", "threads"], s.get("threads", 1), 0, MAX_THREADS,
                        f"an integer from 0 to {MAX_THREADS}")
    return Spec(file=path, base=base, mass_ratio=mu, x_a=x_a, rho_max=rho_max, targets=targets, grids=grids,
                overrides=c.overrides(["sequence", "set"], s.get("set")), threads=threads)


def _base(c: _Checker, path: Path, value) -> Path:
    if not isinstance(value, str) or not value or "\0" in value:
        raise c.fail(["sequence", "base"], "the path of a parameter file, relative to this file", value)
    base = (path.parent / value).resolve()
    try:
        mode = os.stat(base).st_mode
    except OSError as e:
        raise SpecError(f"{path}: sequence.base: {base}: {e.strerror}")
    if not stat.S_ISREG(mode):
        raise SpecError(f"{path}: sequence.base: {base} is not a regular file")
    return base
