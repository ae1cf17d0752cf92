"""The engine benchmark's targets beyond `hdot derive`, and the table of
every target with its figure and whether it is met (`benches/engine_bench.py`
runs it; `scripts/bench` runs that).

Measured here, in the same run as the derivations and their peers:

* `hdot verify NAME` of every bundled derivation (`hdot list`), and `hdot
  verify` of all of them in one process;
* scenes linear in their size: `hdot inertia` of 100,000 point `[[body]]`
  tables, and of a `[[cloud]]` of 100,000 particles read from CSV (both
  made here, with a seeded generator, in a temporary folder);
* the compiled derived right-hand side of the heavy top against the
  hand-written model of the same top (`crates/sim/benches/derived_rhs.rs`
  in its loop mode, `HDOT_RHS_LOOP`): CPU time per evaluation, the
  difference of a run of 2N evaluations and one of N, so that the start-up
  and the model's compilation cancel (the least of five runs of each, the
  lines interleaved).

Every time is CPU time (user + system) of the process, the median of
several runs, as the derivations' are.
"""

from __future__ import annotations

import json
import os
import random
import subprocess
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent

# The targets, each (what is measured, the bound): the one place they are
# written; the report reads them.
CHAIN8_SECONDS = 0.3
CHAIN8_MEGABYTES = 100
SYMPY_RATIO = 300
SYMBOLICA_RATIO = 4
SUM_SECONDS = 1.0
VERIFY_EACH_SECONDS = 0.3
VERIFY_ALL_SECONDS = 2.0
SCENE_SECONDS = 1.0
SCENE_SIZE = 100_000
RHS_SOLVED_RATIO = 1.5
RHS_MASS_MATRIX_RATIO = 2.0

# The lines of the right-hand-side bench compared (HDOT_RHS_LOOP=list).
RHS_HAND = "hand-written, Eulerian angles"
RHS_SOLVED = "derived, solved accelerations"
RHS_MASS_MATRIX = "derived, mass-matrix form"


def add_arguments(ap):
    """The options of this part of the benchmark."""
    ap.add_argument("--no-verify", action="store_true", help="skip `hdot verify`")
    ap.add_argument("--no-scenes", action="store_true", help="skip the 100,000-body scenes")
    ap.add_argument("--no-rhs", action="store_true",
                    help="skip the derived right-hand side (it builds the bench binary first)")
    ap.add_argument("--verify-runs", type=int, default=3, help="runs per `hdot verify` (median)")
    ap.add_argument("--rhs-count", type=int, default=10_000_000,
                    help="evaluations N of the right-hand side (runs of N and 2N are timed)")


def bundled(exe):
    """The names of the bundled derivation files, as `hdot list` gives them
    (not the generated families, such as chain-K)."""
    out = subprocess.run([exe, "list"], cwd=ROOT, capture_output=True, text=True, check=True)
    names = [line.split()[0] for line in out.stdout.splitlines() if line and not line[0].isspace()]
    return [n for n in names if (ROOT / "derivations" / f"{n}.toml").is_file()]


def bodies_scene(folder, n, rng):
    """A scene of n point `[[body]]` tables (a mass and a position each)."""
    path = folder / f"bodies-{n}.toml"
    parts = [f'name = "{n} point bodies"\n']
    for i in range(n):
        x, y, z = (rng.uniform(-1, 1) for _ in range(3))
        parts.append(f'[[body]]\nname = "p{i}"\nshape = "point"\nmass = {rng.uniform(0.1, 2):.6g}\n'
                     f"position = [{x:.6g}, {y:.6g}, {z:.6g}]\n")
    path.write_text("".join(parts))
    return path


def cloud_scene(folder, n, rng):
    """A scene of one `[[cloud]]` of n particles, `x,y,z,m` lines of CSV."""
    csv = folder / f"cloud-{n}.csv"
    csv.write_text("".join(f"{rng.uniform(-1, 1):.6g},{rng.uniform(-1, 1):.6g},"
                           f"{rng.uniform(-1, 1):.6g},{rng.uniform(0.1, 2):.6g}\n" for _ in range(n)))
    path = folder / f"cloud-{n}.toml"
    path.write_text(f'name = "a cloud of {n} particles"\n\n[[cloud]]\nfile = "{csv.name}"\n')
    return path


def rhs_binary():
    """The right-hand-side bench binary, built (bench profile) if needed."""
    print("building the right-hand-side bench (cargo bench --workspace --bench derived_rhs "
          "--no-run)...", flush=True)
    out = subprocess.run(
        ["cargo", "bench", "--workspace", "--bench", "derived_rhs", "--no-run",
         "--message-format=json"],
        cwd=ROOT, capture_output=True, text=True, check=True,
    )
    for line in out.stdout.splitlines():
        msg = json.loads(line)
        if (msg.get("reason") == "compiler-artifact" and msg.get("executable")
                and msg["target"]["name"] == "derived_rhs"):
            return msg["executable"]
    raise SystemExit("bench_targets: cargo built no derived_rhs executable")


def per_evaluation(binary, lines, count, run_process, runs=5):
    """CPU seconds per evaluation of each line of the right-hand-side bench:
    the least CPU time of `runs` runs of 2N evaluations less the least of
    `runs` runs of N (a loop of ~30 ns evaluations is slowed, never sped
    up, by what else the host does; the lines are interleaved, so a slow
    spell falls on all of them)."""
    best = {(line, n): float("inf") for line in lines for n in (count, 2 * count)}
    for _ in range(runs):
        for line, n in best:
            env = dict(os.environ, HDOT_RHS_LOOP=line, HDOT_RHS_COUNT=str(n))
            best[line, n] = min(best[line, n], run_process([binary], env=env)[0])
    return {line: (best[line, 2 * count] - best[line, count]) / count for line in lines}


def fmt(s):
    """Seconds, in the unit that reads best."""
    return f"{s * 1e3:.1f} ms" if s < 1 else f"{s:.2f} s"


def report(exe, hd, rows, args, run_process, median_runs):
    """Measures the targets beyond `hdot derive` and returns the Markdown
    lines of the targets table (`hd`: derive workload → (CPU s, peak bytes,
    wall s); `rows`: (workload, peer, peer CPU s, terms, rounds, ratio))."""
    targets = []  # (target, figure, met: True/False/None)

    def peer_ratio(name, peer, bound):
        t = hd.get(name)
        mine = [r for r in rows if r[0] == name and r[1] == peer]
        if t is None or not mine:
            targets.append((f"{name} at least {bound}× faster than {peer}", "not measured", None))
            return
        ratio = mine[0][5]
        targets.append((f"{name} at least {bound}× faster than {peer}", f"{ratio:,.1f}×", ratio >= bound))

    peer_ratio("gyroscope", "SymPy", SYMPY_RATIO)
    peer_ratio("chain-4", "SymPy", SYMPY_RATIO)
    peer_ratio("chain-6", "Symbolica", SYMBOLICA_RATIO)
    if "chain-8" in hd:
        t, rss, _ = hd["chain-8"]
        targets.append((f"chain-8 under {CHAIN8_SECONDS} s", fmt(t), t < CHAIN8_SECONDS))
        targets.append((f"chain-8 under {CHAIN8_MEGABYTES} MB", f"{rss / 1e6:.0f} MB",
                        rss / 1e6 < CHAIN8_MEGABYTES))
    for name in hd:
        if name.startswith("sum-"):
            t = hd[name][0]
            targets.append((f"a {name[4:]}-term sum under {SUM_SECONDS:g} s", fmt(t), t < SUM_SECONDS))
    if "bicycle" in hd:
        targets.append(("the bicycle's peak memory (recorded)", f"{hd['bicycle'][1] / 1e6:.0f} MB", None))

    def cpu(argv, runs, budget=30.0):
        return median_runs(lambda: run_process(argv), runs, budget)[0][0]

    if not args.no_verify:
        each = []
        for name in bundled(exe):
            t = cpu([exe, "verify", name], args.verify_runs)
            each.append((t, name))
            print(f"hdot verify {name:<36} CPU {fmt(t):>9}", flush=True)
        slow = [f"{n} {fmt(t)}" for t, n in sorted(each, reverse=True) if t >= VERIFY_EACH_SECONDS]
        worst = max(each)
        figure = f"slowest {worst[1]} {fmt(worst[0])}" + (f"; over: {', '.join(slow)}" if slow else "")
        targets.append((f"`hdot verify` of every bundled file under {VERIFY_EACH_SECONDS} s",
                        figure, not slow))
        t = cpu([exe, "verify"], args.verify_runs)
        print(f"hdot verify (all bundled) CPU {fmt(t)}", flush=True)
        targets.append((f"`hdot verify` of all bundled files under {VERIFY_ALL_SECONDS:g} s",
                        fmt(t), t < VERIFY_ALL_SECONDS))
    if not args.no_scenes:
        rng = random.Random(25)
        with tempfile.TemporaryDirectory(prefix="hdot-bench-") as d:
            for what, make in (("point `[[body]]` tables", bodies_scene),
                               ("`[[cloud]]` particles", cloud_scene)):
                path = make(Path(d), SCENE_SIZE, rng)
                t = cpu([exe, "inertia", str(path)], 3)
                print(f"hdot inertia, {SCENE_SIZE:,} {what}: CPU {fmt(t)}", flush=True)
                targets.append((f"{SCENE_SIZE:,} {what} under {SCENE_SECONDS:g} s", fmt(t),
                                t < SCENE_SECONDS))
    if not args.no_rhs:
        binary = rhs_binary()
        per = per_evaluation(binary, (RHS_HAND, RHS_SOLVED, RHS_MASS_MATRIX), args.rhs_count,
                             run_process)
        for line, t in per.items():
            print(f"rhs {line:<32} {t * 1e9:6.1f} ns per evaluation", flush=True)
        for line, bound in ((RHS_SOLVED, RHS_SOLVED_RATIO), (RHS_MASS_MATRIX, RHS_MASS_MATRIX_RATIO)):
            ratio = per[line] / per[RHS_HAND]
            targets.append((f"heavy top's right-hand side, {line}, within {bound:g}× of the "
                            "hand-written", f"{ratio:.2f}× ({per[line] * 1e9:.0f} against "
                            f"{per[RHS_HAND] * 1e9:.0f} ns)", ratio <= bound))
    met = sum(1 for t in targets if t[2] is True)
    judged = sum(1 for t in targets if t[2] is not None)
    how = [f"Targets of this run ({met} of {judged} met)."]
    if not args.no_verify:
        how.append(f"`hdot verify`: CPU time, median of {args.verify_runs} runs per bundled file "
                   "and of all in one process.")
    if not args.no_scenes:
        how.append(f"Scenes: `hdot inertia` of {SCENE_SIZE:,} point bodies and of a cloud of as "
                   "many particles from CSV, median of 3.")
    if not args.no_rhs:
        how.append("Right-hand side: CPU time per evaluation of `crates/sim/benches/derived_rhs.rs` "
                   f"in its loop mode, runs of {2 * args.rhs_count:,} less runs of "
                   f"{args.rhs_count:,} evaluations, the least of 5 of each, the lines interleaved.")
    lines = [
        "",
        " ".join(how),
        "",
        "| target | this run | met? |",
        "|---|---|---|",
    ]
    for what, figure, ok in targets:
        lines.append(f"| {what} | {figure} | {'—' if ok is None else ('yes' if ok else '**no**')} |")
    return lines
