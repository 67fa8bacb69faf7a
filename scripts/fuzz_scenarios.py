#!/usr/bin/env python3
"""Fuzz campaign for platoonsim's scenario input (issue 18 item 6; docs/robustness.md).

Mutates the built-in scenarios (crates/scenario/scenarios/*.toml with a [run], [road] or
[network] section) and runs the release binary on each mutant:

* parser cases:  platoonsim show FILE                  (and show BUILTIN --set KEY=VALUE)
* run cases:     platoonsim run FILE --duration 60 --warmup 0 -q --out TMP

each with a wall-clock timeout and an address-space limit (RLIMIT_AS). A violation is a panic
(exit code 101 or 'panicked' in stderr), a process killed by the timeout or by a signal (the
memory limit ends an allocation with an abort), or a refusal without an error message. A run
that exits 0 although its summary.json counts collisions is reported separately
(--strict-collisions makes it a violation).

Deterministic for a given --seed. Prints the counts; exit status 1 on any violation, and the
offending inputs are kept in --keep. Standard library only (Python 3.11).

    cargo build --release
    python3 scripts/fuzz_scenarios.py --seed 1 --cases 10000 --runs 400
"""

import argparse
import concurrent.futures
import json
import os
import random
import re
import resource
import shutil
import subprocess
import sys
import tempfile
import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
SCENARIOS = ROOT / "crates" / "scenario" / "scenarios"

# Replacements for a number or a whole value: zero, negatives, huge, tiny, non-finite, wrong
# types, the known reproductions and values just outside the documented limits.
MUTANTS = [
    "0", "-1", "-0.0", "1e300", "-1e300", "1e-300", "nan", "inf", "-inf", "+inf",
    "4294967296", "9223372036854775807", "-9223372036854775808", "18446744073709551616",
    "1e12", "604801", "0.049", "0.11", "0.05", "1", "10001", "200001", "1e7",
    '"x"', '""', "[]", "[1, 2]", "[[0.6, 1.0]]", "[nan]", "true", "{ a = 1 }",
    "1979-05-27T07:32:00Z", "0x10", "1_000", "'''\nx'''",
]
NUMBER = re.compile(r"(?<![\w.])[-+]?\d[\d_]*(\.\d+)?([eE][-+]?\d+)?(?![\w.])")
KEY_LINE = re.compile(r"^\s*[A-Za-z_][\w.]*\s*=.*$", re.M)
HEADER = re.compile(r"^\s*\[\[?[\w.]+\]\]?\s*$", re.M)


def scenario_files():
    """The built-in scenario files (not the threshold and demand-scale tables)."""
    out = []
    for p in sorted(SCENARIOS.glob("*.toml")):
        doc = tomllib.loads(p.read_text())
        if any(k in doc for k in ("run", "road", "network")):
            out.append(p)
    return out


def leaf_keys(v, prefix=""):
    """Every leaf key path of a parsed document, in --set syntax."""
    if isinstance(v, dict):
        for k, x in v.items():
            yield from leaf_keys(x, f"{prefix}.{k}" if prefix else k)
    elif isinstance(v, list) and v and all(isinstance(x, dict) for x in v):
        for i, x in enumerate(v):
            yield from leaf_keys(x, f"{prefix}[{i}]")
    else:
        yield prefix


def huge_array(r, in_arg=False):
    # One command-line argument is at most 128 KiB on Linux: a --set value stays below it.
    n = r.choice([101, 10_081, 40_000 if in_arg else 300_000])
    return "[" + ", ".join(["1"] * n) + "]"


def mutate(text, r, mild):
    """One mutant of a scenario text. `mild`: numbers scaled by a factor in [0.5, 2] (mostly
    still valid, so that runs reach the engine)."""
    if mild:
        nums = list(NUMBER.finditer(text))
        for _ in range(r.randint(1, 3)):
            m = r.choice(nums)
            v = float(m.group(0).replace("_", "")) * r.uniform(0.5, 2.0)
            text = text[: m.start()] + repr(v) + text[m.end():]
            nums = list(NUMBER.finditer(text))
        return text
    kind = r.randrange(9)
    if kind == 0:  # a number replaced
        nums = list(NUMBER.finditer(text))
        m = r.choice(nums)
        return text[: m.start()] + r.choice(MUTANTS) + text[m.end():]
    if kind == 1:  # a whole value replaced
        lines = list(KEY_LINE.finditer(text))
        m = r.choice(lines)
        key = m.group(0).split("=", 1)[0]
        value = r.choice(MUTANTS) if r.random() < 0.9 else huge_array(r)
        return text[: m.start()] + f"{key}= {value}" + text[m.end():]
    if kind == 2:  # a key deleted
        m = r.choice(list(KEY_LINE.finditer(text)))
        return text[: m.start()] + text[m.end():]
    if kind == 3:  # a table duplicated (with its keys)
        heads = list(HEADER.finditer(text))
        if not heads:
            return text + "\n[run]\n"
        i = r.randrange(len(heads))
        end = heads[i + 1].start() if i + 1 < len(heads) else len(text)
        return text + "\n" + text[heads[i].start():end]
    if kind == 4:  # truncated
        return text[: r.randrange(len(text))]
    if kind == 5:  # random bytes (may not be UTF-8)
        b = bytearray(text.encode())
        for _ in range(r.randint(1, 8)):
            b[r.randrange(len(b))] = r.randrange(256)
        return bytes(b)
    if kind == 6:  # two lines swapped
        lines = text.split("\n")
        i, j = r.randrange(len(lines)), r.randrange(len(lines))
        lines[i], lines[j] = lines[j], lines[i]
        return "\n".join(lines)
    if kind == 7:  # a new key with a mutant value in an existing table
        heads = list(HEADER.finditer(text))
        key = r.choice(["dt_s", "duration_s", "demand_vph", "time_gap_shares", "lanes",
                        "length_m", "max_platoon", "x", "count"])
        value = r.choice(MUTANTS) if r.random() < 0.8 else huge_array(r)
        if heads:
            h = r.choice(heads)
            return text[: h.end()] + f"\n{key} = {value}" + text[h.end():]
        return f"{key} = {value}\n" + text
    # several numbers replaced at once
    for _ in range(r.randint(2, 6)):
        nums = list(NUMBER.finditer(text))
        m = r.choice(nums)
        text = text[: m.start()] + r.choice(MUTANTS) + text[m.end():]
    return text


def limit(mem_bytes):
    def apply():
        resource.setrlimit(resource.RLIMIT_AS, (mem_bytes, mem_bytes))
        resource.setrlimit(resource.RLIMIT_CORE, (0, 0))
    return apply


def execute(case, args):
    """Run one case; returns (case, outcome, detail). outcome: ok | refused | violation |
    collision-exit-0."""
    kind, argv, workdir = case["kind"], case["argv"], case["dir"]
    try:
        p = subprocess.run([args.bin] + argv, cwd=workdir, capture_output=True,
                           timeout=args.timeout, preexec_fn=limit(args.mem_gib << 30))
    except subprocess.TimeoutExpired:
        return case, "violation", f"timeout after {args.timeout} s"
    except OSError as e:  # e.g. an argument the OS refuses: not the program's fault
        return case, "not-started", str(e)
    err = p.stderr.decode(errors="replace")
    if p.returncode == 101 or "panicked" in err:
        return case, "violation", "panic: " + err[-2000:]
    if p.returncode < 0:
        return case, "violation", f"killed by signal {-p.returncode}: " + err[-2000:]
    if p.returncode != 0:
        if "error" not in err.lower():
            return case, "violation", f"exit {p.returncode} without an error message"
        return case, "refused", err
    if kind == "run":
        summary = Path(workdir) / "out" / "summary.json"
        try:
            collisions = json.loads(summary.read_text()).get("collisions", 0)
        except (OSError, ValueError) as e:
            return case, "violation", f"exit 0 but no readable summary.json ({e})"
        if collisions > 0:
            return case, "collision-exit-0", f"collisions = {collisions}, exit 0"
    return case, "ok", ""


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--cases", type=int, default=10_000, help="parser cases (show)")
    ap.add_argument("--runs", type=int, default=400, help="short runs among them")
    ap.add_argument("--bin", default=str(ROOT / "target" / "release" / "platoonsim"))
    ap.add_argument("--run-duration", type=float, default=60.0,
                    help="simulated seconds of the short runs")
    ap.add_argument("--timeout", type=float, default=20.0, help="seconds per process")
    ap.add_argument("--mem-gib", type=int, default=4, help="address-space limit per process")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--keep", default="fuzz-failures", help="directory for offending inputs")
    ap.add_argument("--strict-collisions", action="store_true",
                    help="a run that collides and exits 0 is a violation")
    args = ap.parse_args()
    if not Path(args.bin).is_file():
        sys.exit(f"{args.bin} not found: run cargo build --release first")

    r = random.Random(args.seed)
    files = scenario_files()
    texts = {p.stem: p.read_text() for p in files}
    keys = {p.stem: list(leaf_keys(tomllib.loads(texts[p.stem]))) for p in files}
    builtins = [s for s in ("homogeneous", "sr99") if s in texts]
    tmp = Path(tempfile.mkdtemp(prefix="platoonsim-fuzz-"))
    cases = []
    for i in range(args.cases + args.runs):
        d = tmp / f"c{i}"
        d.mkdir()
        if i >= args.cases:  # a short run of a mildly or strongly mutated file
            stem = r.choice(list(texts))
            body = mutate(texts[stem], r, mild=r.random() < 0.7)
            f = d / f"{stem}.toml"
            f.write_bytes(body if isinstance(body, bytes) else body.encode())
            argv = ["run", str(f), "--duration", f"{args.run_duration:g}", "--warmup", "0", "-q",
                    "--out", "out"]
            cases.append({"kind": "run", "argv": argv, "dir": str(d), "seed_of": stem})
        elif r.random() < 0.25:  # --set on a built-in
            name = r.choice(builtins)
            key = r.choice(keys[name])
            value = r.choice(MUTANTS) if r.random() < 0.95 else huge_array(r, in_arg=True)
            argv = ["show", name, "--set", f"{key}={value}"]
            cases.append({"kind": "set", "argv": argv, "dir": str(d), "seed_of": name})
        else:  # show of a mutated file
            stem = r.choice(list(texts))
            body = mutate(texts[stem], r, mild=r.random() < 0.1)
            f = d / f"{stem}.toml"
            f.write_bytes(body if isinstance(body, bytes) else body.encode())
            cases.append({"kind": "show", "argv": ["show", str(f)], "dir": str(d),
                          "seed_of": stem})

    counts = {}
    violations, collisions = [], []
    with concurrent.futures.ThreadPoolExecutor(args.jobs) as pool:
        for case, outcome, detail in pool.map(lambda c: execute(c, args), cases):
            counts[(case["kind"], outcome)] = counts.get((case["kind"], outcome), 0) + 1
            if outcome == "violation":
                violations.append((case, detail))
            elif outcome == "collision-exit-0":
                collisions.append((case, detail))
    keep = Path(args.keep)
    for n, (case, detail) in enumerate(violations + collisions):
        dst = keep / f"case{n}"
        shutil.copytree(case["dir"], dst, dirs_exist_ok=True, ignore=shutil.ignore_patterns("out"))
        argv = [a.replace(case["dir"], str(dst.resolve())) for a in case["argv"]]
        (dst / "REPRODUCE.txt").write_text(
            "platoonsim " + " ".join(argv) + "\n\n" + detail + "\n")
    shutil.rmtree(tmp, ignore_errors=True)

    print(f"seed {args.seed}: {len(cases)} cases ({args.cases} parser, {args.runs} runs), "
          f"timeout {args.timeout:g} s, address space {args.mem_gib} GiB")
    for kind in ("show", "set", "run"):
        row = {o: n for (k, o), n in counts.items() if k == kind}
        print(f"  {kind:5}: " + ", ".join(f"{o} {n}" for o, n in sorted(row.items())))
    print(f"  violations: {len(violations)}")
    print(f"  runs that counted collisions and exited 0: {len(collisions)}"
          + ("" if args.strict_collisions else " (reported, not a violation)"))
    for case, detail in violations[:20]:
        print(f"    platoonsim {' '.join(case['argv'])}: {detail.splitlines()[0][:200]}")
    if violations or collisions:
        print(f"  inputs kept in {keep}/")
    bad = violations or (args.strict_collisions and collisions)
    sys.exit(1 if bad else 0)


if __name__ == "__main__":
    main()
