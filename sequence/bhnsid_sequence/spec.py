"""The sequence file (sequence/README.md): a base parameter file, mu_bn, the xhat_A list, the
rho_max list or range, the target rest masses and the grid configurations of the error model.
Bad input is one SpecError naming the file, the key and what was expected."""
from dataclasses import dataclass, field
from pathlib import Path
from typing import Dict, List

import yaml

# The paper's Table III: the grid configurations per mu_bn, the finest (the tabulated one) first.
PAPER_GRIDS = {
    1.0: [(256, 0.015), (128, 0.03), (160, 0.015)],
    3.0: [(256, 0.015), (128, 0.03), (160, 0.015)],
    10.0: [(256, 0.01), (128, 0.02), (160, 0.014375)],
}


class SpecError(Exception):
    pass


@dataclass(frozen=True)
class Grid:
    n: int
    dx: float

    @property
    def rc(self) -> float:
        return self.n * self.dx / 2

    @property
    def name(self) -> str:
        return f"n{self.n}_dx{self.dx:g}"


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


def _numbers(file, key, value, lo=None, hi=None):
    if isinstance(value, dict):
        try:
            start, stop, count = float(value["from"]), float(value["to"]), int(value["count"])
        except (KeyError, TypeError, ValueError):
            raise SpecError(f"{file}: {key}: expected a list of numbers or {{from: A, to: B, count: N}}")
        if count < 2 or not stop > start:
            raise SpecError(f"{file}: {key}: expected from < to and count >= 2")
        value = [start + (stop - start) * i / (count - 1) for i in range(count)]
    if not isinstance(value, list) or not value or not all(isinstance(v, (int, float)) and not isinstance(v, bool)
                                                           for v in value):
        raise SpecError(f"{file}: {key}: expected a non-empty list of numbers, got {value!r}")
    out = [float(v) for v in value]
    for v in out:
        if (lo is not None and v < lo) or (hi is not None and v > hi):
            raise SpecError(f"{file}: {key}: {v} is outside [{lo}, {hi}]")
    if len(set(out)) != len(out):
        raise SpecError(f"{file}: {key}: a value is listed twice")
    return out


def read_spec(path) -> Spec:
    path = Path(path)
    try:
        text = path.read_text()
    except OSError as e:
        raise SpecError(f"{path}: cannot read the sequence file: {e.strerror}")
    try:
        doc = yaml.safe_load(text)
    except yaml.YAMLError as e:
        raise SpecError(f"{path}: not valid YAML: {e}")
    if not isinstance(doc, dict) or not isinstance(doc.get("sequence"), dict):
        raise SpecError(f"{path}: expected a mapping with a section 'sequence'")
    s = doc["sequence"]
    known = {"base", "mass_ratio", "x_a", "rho_max", "targets", "grids", "set", "threads"}
    for key in s:
        if key not in known:
            raise SpecError(f"{path}: sequence.{key}: unknown key; expected one of {', '.join(sorted(known))}")
    for key in ("base", "mass_ratio", "x_a", "rho_max", "targets"):
        if key not in s:
            raise SpecError(f"{path}: sequence.{key}: missing")
    base = (path.parent / str(s["base"])).resolve()
    if not base.is_file():
        raise SpecError(f"{path}: sequence.base: {base} is not a file")
    mu = s["mass_ratio"]
    if not isinstance(mu, (int, float)) or isinstance(mu, bool) or not mu > 0:
        raise SpecError(f"{path}: sequence.mass_ratio: expected a number > 0, got {mu!r}")
    grids_in = s.get("grids")
    if grids_in is None:
        if float(mu) not in PAPER_GRIDS:
            raise SpecError(f"{path}: sequence.grids: missing, and the paper gives none for mass_ratio = {mu} "
                            f"(only {', '.join(str(k) for k in PAPER_GRIDS)})")
        grids = [Grid(n, dx) for n, dx in PAPER_GRIDS[float(mu)]]
    else:
        if not isinstance(grids_in, list) or not grids_in:
            raise SpecError(f"{path}: sequence.grids: expected a list of {{n: N, dx: DX}}, finest first")
        grids = []
        for i, g in enumerate(grids_in):
            try:
                grids.append(Grid(int(g["n"]), float(g["dx"])))
            except (KeyError, TypeError, ValueError):
                raise SpecError(f"{path}: sequence.grids[{i}]: expected {{n: N, dx: DX}}, got {g!r}")
            if grids[-1].n < 4 or grids[-1].n % 2 or not grids[-1].dx > 0:
                raise SpecError(f"{path}: sequence.grids[{i}]: expected an even n >= 4 and dx > 0")
    overrides = s.get("set", {}) or {}
    if not isinstance(overrides, dict):
        raise SpecError(f"{path}: sequence.set: expected a mapping section.key: value")
    threads = s.get("threads", 1)
    if not isinstance(threads, int) or isinstance(threads, bool) or threads < 0:
        raise SpecError(f"{path}: sequence.threads: expected an integer >= 0")
    return Spec(file=path, base=base, mass_ratio=float(mu), x_a=_numbers(path, "sequence.x_a", s["x_a"], -1, 1),
                rho_max=sorted(_numbers(path, "sequence.rho_max", s["rho_max"], 0)),
                targets=_numbers(path, "sequence.targets", s["targets"], 0, 1), grids=grids,
                overrides={str(k): (str(v).lower() if isinstance(v, bool) else str(v)) for k, v in overrides.items()},
                threads=threads)
