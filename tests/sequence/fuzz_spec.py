"""A seeded mutation fuzz of the sequence-file parser (bhnsid_sequence.spec.read_spec): inputs grown
from the corpus in tests/sequence/corpus/ by byte, token, line and number mutations and splices.
Every input must give a Spec whose values hold the promises (finite numbers in range, bounded
lists, even grid sizes, a run directory of its own for every configuration) or one SpecError of
one line; never another exception, and never more than a second. A failing input is written to
WORK_DIR/failures/ to be added to the corpus once fixed.

usage: fuzz_spec.py WORK_DIR [INPUTS [SEED]]   (default 4000 inputs, seed 1)"""
import math
import random
import shutil
import sys
import time
import traceback
from pathlib import Path

here = Path(__file__).resolve().parent
sys.path.insert(0, str(here.parents[1] / "sequence"))
from bhnsid_sequence.runs import configurations  # noqa: E402
from bhnsid_sequence.spec import MAX_CONFIGURATIONS, MAX_GRIDS, MAX_VALUES, Spec, SpecError, read_spec  # noqa: E402

TOKENS = [b"&a ", b"*a", b"!!str ", b"!custom ", b"[", b"]", b"{", b"}", b": ", b"- ", b"\n", b"\t", b"'", b'"',
          b".nan", b".inf", b"-.inf", b"1e400", b"1e-400", b"0x10", b"1_000", b"1:30", b"~", b"null", b"true", b"yes",
          b"---\n", b"...\n", b"%YAML 1.2\n", b"\x00", b"\xff", b"\xc3\x28", b"9" * 30, b"from: ", b"to: ", b"count: ",
          b"n: ", b"dx: ", b"base: ", b"set: {", b"sequence:", b"grids: [", b"? ", b"|\n", b">\n", b"#", b"\xef\xbb\xbf",
          b"<<: ", b"=", b"\\", b"\r", b"\x1b[31m", b"$(touch PWNED)", b"/dev/zero", b"-0.0", b"1e-320", b"2.0e+12"]
NUMBERS = [b"0", b"-1", b"1", b"2", b"4", b"64.5", b"1e12", b"1.0e+12", b".nan", b".inf", b"1e400", b"5e-324",
           b"0.1000001", b"200", b"201", b"5001", b"9" * 25, b"-0", b"3", b"1.0", b"0.1"]


def mutate(rng: random.Random, data: bytes, corpus) -> bytes:
    for _ in range(rng.choice((1, 1, 2, 3, 5))):
        kind = rng.randrange(8)
        i = rng.randrange(len(data) + 1)
        if kind == 0 and data:
            j = min(len(data), i + rng.randrange(1, 8))
            data = data[:i] + data[j:]
        elif kind == 1:
            data = data[:i] + rng.choice(TOKENS) + data[i:]
        elif kind == 2 and data:
            k = rng.randrange(len(data))
            data = data[:k] + bytes([rng.randrange(256)]) + data[k + 1:]
        elif kind == 3:
            lines = data.split(b"\n")
            a, b = rng.randrange(len(lines)), rng.randrange(len(lines))
            lines[a], lines[b] = lines[b], lines[a]
            data = b"\n".join(lines)
        elif kind == 4:
            other = rng.choice(corpus).split(b"\n")
            lines = data.split(b"\n")
            lines.insert(rng.randrange(len(lines) + 1), rng.choice(other))
            data = b"\n".join(lines)
        elif kind == 5:
            digits = [k for k, c in enumerate(data) if 48 <= c <= 57]
            if digits:
                k = rng.choice(digits)
                end = k
                while end < len(data) and data[end] in b"0123456789.e+-":
                    end += 1
                data = data[:k] + rng.choice(NUMBERS) + data[end:]
        elif kind == 6 and data:
            j = min(len(data), i + rng.randrange(1, 40))
            data = data[:i] + data[i:j] * rng.randrange(2, 50) + data[i:]
        elif kind == 7:
            lines = data.split(b"\n")
            a = rng.randrange(len(lines))
            lines[a] = b" " * rng.randrange(0, 6) + lines[a].lstrip()
            data = b"\n".join(lines)
    return data


def promises(spec: Spec):
    """What a parsed Spec must hold; the first broken promise, or None."""
    numbers = [spec.mass_ratio] + spec.x_a + spec.rho_max + spec.targets + [g.dx for g in spec.grids]
    if not all(isinstance(v, float) and math.isfinite(v) for v in numbers):
        return "a number that is not finite"
    if not (spec.mass_ratio > 0 and all(-1 <= v <= 1 for v in spec.x_a) and all(v > 0 for v in spec.rho_max)
            and all(0 < v <= 1 for v in spec.targets) and all(g.dx > 0 for g in spec.grids)):
        return "a value out of its range"
    if not all(isinstance(g.n, int) and not isinstance(g.n, bool) and g.n >= 4 and g.n % 2 == 0 for g in spec.grids):
        return "a grid size that is not an even integer >= 4"
    if max(len(spec.x_a), len(spec.rho_max), len(spec.targets)) > MAX_VALUES or len(spec.grids) > MAX_GRIDS:
        return "a list over its bound"
    configs = configurations(spec)
    if len(configs) > MAX_CONFIGURATIONS or len({c.relative_dir for c in configs}) != len(configs):
        return "too many configurations, or two sharing a run directory"
    if spec.rho_max != sorted(spec.rho_max) or not isinstance(spec.threads, int) or spec.threads < 0:
        return "rho_max unsorted or threads not a count"
    if not all(isinstance(k, str) and isinstance(v, str) and "\n" not in v for k, v in spec.overrides.items()):
        return "an override that is not one line of text"
    return None


def main():
    work = Path(sys.argv[1]).resolve()
    inputs = int(sys.argv[2]) if len(sys.argv) > 2 else 4000
    seed = int(sys.argv[3]) if len(sys.argv) > 3 else 1
    shutil.rmtree(work, ignore_errors=True)
    (work / "failures").mkdir(parents=True)
    (work / "base.yaml").write_text("grid: {n: 24}\n")
    corpus = [p.read_bytes() for p in sorted((here / "corpus").glob("*.yaml"))]
    rng = random.Random(seed)
    target = work / "spec.yaml"
    failures, parsed, slowest = 0, 0, 0.0
    for k in range(inputs):
        data = corpus[k] if k < len(corpus) else mutate(rng, rng.choice(corpus), corpus)
        target.write_bytes(data)
        start = time.monotonic()
        problem = None
        try:
            problem = promises(read_spec(target))
            parsed += 1
        except SpecError as e:
            if "\n" in str(e) or not str(e).startswith(str(target)):
                problem = f"an error that is not one line naming the file: {str(e)[:200]!r}"
        except Exception:
            problem = traceback.format_exc(limit=3)
        seconds = time.monotonic() - start
        slowest = max(slowest, seconds)
        if seconds > 1.0:
            problem = (problem or "") + f" took {seconds:.2f} s"
        if problem:
            failures += 1
            (work / "failures" / f"input_{k}.yaml").write_bytes(data)
            print(f"FAIL input {k} (seed {seed}): {problem}")
    print(f"{inputs} inputs (seed {seed}): {parsed} parsed, {inputs - parsed - failures} refused with one line, "
          f"{failures} failed; slowest {slowest * 1000:.0f} ms")
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
