#!/usr/bin/env python3
"""Times hdot and sympy.physics.mechanics doing the same derivations.

Issue 3, section 3 ("Speed, side by side"). In one run this script

* times SymPy on three workloads, each written the way a SymPy user would:
  (a) the general Euler equations with products of inertia
      (ReferenceFrame, inertia(), angular velocity, ``dt`` of H in the body
      frame, i.e. the transport theorem; ``expand``);
  (b) the gyroscope equations brought into textbook form (frames by
      ``orient`` 'Axis': phi about N.z, theta about the line of nodes, psi
      about the spin axis; H_O of an axisymmetric rotor; M = dH/dt in N
      expressed in the nutation frame; ``trigsimp``/``simplify``, psi'
      replaced by the abbreviation omega_z, ``collect``);
  (c) ``chain-K`` for K = 1..max-k exactly as ``crates/sym/src/chain.rs``
      defines it (body i turned from body i-1 by q_i about the parent's
      z, x, y, z, ... axis; a general inertia tensor per body in its own
      axes; H = sum I_i . omega_i; H' = H.dt(N); components in N; ``expand``);
* times the hdot release binary on the same work: wall time of
  ``hdot derive NAME --format json`` (a whole process: start-up, parse,
  derive, check, print), best of several runs; and, when criterion results
  are found (``cargo bench -p hdot-sym --bench derive``), the criterion
  median of the in-process benchmark (parse + derive + check + print);
* checks at three seeded random points that hdot's result (its
  ``--format sympy`` export, executed) equals SymPy's;
* prints a table, writes it as CSV to ``docs/perf/compare_sympy.csv`` and
  draws time against K for chain-K (log scale) to ``docs/perf/chain-k.png``
  and ``.svg``.

Usage (from the repository root, after ``scripts/setup``)::

    export CARGO_TARGET_DIR=target          # or wherever you build
    cargo build --release -p hdot
    cargo bench -p hdot-sym --bench derive  # optional: criterion medians
    python3 benches/compare_sympy.py [--max-k 6] [--hdot target/release/hdot]

SymPy needs about half a minute for chain-6 on a 2-core machine; the whole
run takes a few minutes. ``--max-k 4`` makes it quick.
"""

from __future__ import annotations

import argparse
import csv
import json
import math
import os
import random
import re
import subprocess
import sys
import threading
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent

try:
    import sympy as sp
    from sympy.core.cache import clear_cache
    from sympy.core.function import AppliedUndef
    from sympy.physics.mechanics import ReferenceFrame, dynamicsymbols, inertia
except ImportError:  # pragma: no cover - the message is the point
    sys.exit("compare_sympy: sympy is missing; run scripts/setup (pip install 'sympy>=1.12')")


# --------------------------------------------------------------------------
# SymPy workloads. Each returns (components, expanded, abbreviations) where
# `components` is the final result as SymPy leaves it, `expanded` the same
# components as flat sums (used for term counts and for the scale of the
# tolerance) and `abbreviations` maps a function of time introduced for the
# textbook form (omega_z) to what it stands for.
# --------------------------------------------------------------------------


def hdot_inertia(frame, ix, iy, iz, ixy, iyz, izx):
    """hdot's ``inertia(I_x, I_y, I_z, I_xy, I_yz, I_zx)``: products of
    inertia are integrals (I_xy = ∫xy dm) and enter the tensor with a minus
    sign. sympy's ``inertia`` takes the tensor entries themselves."""
    return inertia(frame, ix, iy, iz, -ixy, -iyz, -izx)


def sympy_euler_general():
    """(a) Euler's equations, body axes that are not principal."""
    ix, iy, iz, ixy, iyz, izx = sp.symbols("I_x I_y I_z I_xy I_yz I_zx")
    wx, wy, wz = dynamicsymbols("omega_x omega_y omega_z")
    N = ReferenceFrame("N")
    B = ReferenceFrame("B")
    B.set_ang_vel(N, wx * B.x + wy * B.y + wz * B.z)
    H = hdot_inertia(B, ix, iy, iz, ixy, iyz, izx) & B.ang_vel_in(N)
    M = H.dt(N)  # H is expressed in B: transport theorem
    comps = [sp.expand(M & e) for e in (B.x, B.y, B.z)]
    return comps, comps, {}


def sympy_gyroscope():
    """(b) The gyroscope in the nutation frame, in textbook form."""
    I, Ip = sp.symbols("I Ip")
    phi, theta, psi = dynamicsymbols("phi theta psi")
    omega_z = dynamicsymbols("omega_z")
    N = ReferenceFrame("N")
    P = N.orientnew("P", "Axis", [phi, N.z])  # precession
    F = P.orientnew("F", "Axis", [theta, P.y])  # nutation about the line of nodes
    R = F.orientnew("R", "Axis", [psi, F.z])  # spin
    omega = R.ang_vel_in(N)
    H = inertia(F, Ip, Ip, I) & omega  # axisymmetric: the same in F as in R
    M = H.dt(N)
    raw = [M.express(F) & e for e in (F.x, F.y, F.z)]
    expanded = [sp.expand(c) for c in raw]
    # Textbook form: simplify, then write psi' = omega_z - phi' cos(theta)
    # (and its derivative) so that omega_z appears as in §7, and collect.
    t = dynamicsymbols._t
    to_wz = {
        psi.diff(t, 2): omega_z.diff(t) - sp.diff(phi.diff(t) * sp.cos(theta), t),
        psi.diff(t): omega_z - phi.diff(t) * sp.cos(theta),
    }
    comps = []
    for c in raw:
        c = sp.trigsimp(sp.simplify(c))
        c = sp.expand(c.subs(to_wz))
        c = sp.collect(sp.trigsimp(c), [Ip, I])
        comps.append(c)
    return comps, expanded, {omega_z: psi.diff(t) + phi.diff(t) * sp.cos(theta)}


def sympy_chain(k):
    """(c) chain-K as crates/sym/src/chain.rs defines it."""
    N = ReferenceFrame("N")
    parent = N
    H = 0
    for i in range(1, k + 1):
        q = dynamicsymbols(f"q_{i}")
        axis = getattr(parent, "zxy"[(i - 1) % 3])
        body = parent.orientnew(f"B{i}", "Axis", [q, axis])
        ix, iy, iz, ixy, iyz, izx = sp.symbols(
            f"I_{i}x I_{i}y I_{i}z I_{i}xy I_{i}yz I_{i}zx"
        )
        H = H + (hdot_inertia(body, ix, iy, iz, ixy, iyz, izx) & body.ang_vel_in(N))
        parent = body
    Hdot = H.dt(N)
    comps = [sp.expand(Hdot.express(N) & e) for e in (N.x, N.y, N.z)]
    return comps, comps, {}


# --------------------------------------------------------------------------
# Peers without a mechanics module: SymEngine and Symbolica do chain-K's
# expansion and d/dt on plain symbols (q_i, its rate qd_i and acceleration
# qdd_i; d/dt by the chain rule), the same rotations and inertia tensors.
# --------------------------------------------------------------------------


def chain_h(k, sym, sin, cos):
    """H of chain-K in N on plain symbols, with (q, qd, qdd) per body."""

    def rot(axis, q):
        c, s = cos(q), sin(q)
        if axis == "z":
            return [[c, -s, 0], [s, c, 0], [0, 0, 1]]
        if axis == "x":
            return [[1, 0, 0], [0, c, -s], [0, s, c]]
        return [[c, 0, s], [0, 1, 0], [-s, 0, c]]

    def mat_vec(a, v):
        return [sum(a[i][m] * v[m] for m in range(3)) for i in range(3)]

    def mat_mul(a, b):
        return [[sum(a[i][m] * b[m][j] for m in range(3)) for j in range(3)] for i in range(3)]

    R = [[1, 0, 0], [0, 1, 0], [0, 0, 1]]
    omega, H, rates = [0, 0, 0], [0, 0, 0], []
    for i in range(1, k + 1):
        q, qd, qdd = sym(f"q_{i}"), sym(f"qd_{i}"), sym(f"qdd_{i}")
        rates.append((q, qd, qdd))
        axis = "xyz".index("zxy"[(i - 1) % 3])
        Ri = rot("xyz"[axis], q)
        # ω of body i in its own axes: the parent's turned, plus qd about the axis.
        omega = mat_vec([[Ri[j][m] for j in range(3)] for m in range(3)], omega)
        omega[axis] = omega[axis] + qd
        R = mat_mul(R, Ri)
        ix, iy, iz, ixy, iyz, izx = (sym(f"I_{i}{c}") for c in ("x", "y", "z", "xy", "yz", "zx"))
        inertia_i = [[ix, -ixy, -izx], [-ixy, iy, -iyz], [-izx, -iyz, iz]]
        h = mat_vec(R, mat_vec(inertia_i, omega))
        H = [H[j] + h[j] for j in range(3)]
    return H, rates


def chain_hdot(H, rates, diff, expand):
    """Ḣ = Σ ∂H/∂q q̇ + ∂H/∂q̇ q̈, each component expanded."""
    out = []
    for h in H:
        h = expand(h)
        d = 0
        for q, qd, qdd in rates:
            d = d + diff(h, q) * qd + diff(h, qd) * qdd
        out.append(expand(d))
    return out


def peer_chain_symengine(k):
    """chain-K in SymEngine: (seconds, terms)."""
    import symengine as se

    t0 = time.perf_counter()
    H, rates = chain_h(k, se.Symbol, se.sin, se.cos)
    res = chain_hdot(H, rates, lambda e, x: e.diff(x), se.expand)
    dt = time.perf_counter() - t0
    return dt, sum(len(r.args) if isinstance(r, se.Add) else 1 for r in res)


def peer_chain_symbolica(k):
    """chain-K in Symbolica: (seconds, terms)."""
    from symbolica import E, S

    sin, cos = S("sin"), S("cos")
    t0 = time.perf_counter()
    H, rates = chain_h(k, S, lambda q: sin(q), lambda q: cos(q))
    H = [E("0") + h for h in H]
    res = chain_hdot(H, rates, lambda e, x: e.derivative(x), lambda e: e.expand())
    dt = time.perf_counter() - t0
    terms = 0
    for r in res:
        terms += len(r) if str(r.get_type()).endswith("Add") else 1
    return dt, terms


# --------------------------------------------------------------------------
# hdot
# --------------------------------------------------------------------------


def hdot_time(exe, name, runs):
    """Best wall time of `hdot derive NAME --format json`, and its JSON."""
    best, out = math.inf, None
    for _ in range(runs):
        t0 = time.perf_counter()
        res = subprocess.run(
            [exe, "derive", name, "--format", "json"],
            cwd=ROOT, capture_output=True, text=True, check=True,
        )
        best = min(best, time.perf_counter() - t0)
        out = res.stdout
    return best, json.loads(out)


def hdot_equations(exe, name):
    """Runs `hdot derive NAME --format sympy` and executes the export.

    Returns ({"step.component": rhs}, abbreviations)."""
    src = subprocess.run(
        [exe, "derive", name, "--format", "sympy"],
        cwd=ROOT, capture_output=True, text=True, check=True,
    ).stdout
    # A label with a prime (chain-K's H') is exported as Symbol('H'_x'),
    # which is not Python; the left-hand side is not compared, so quote it.
    src = re.sub(
        r"Eq\(Symbol\('(.*?)'\), ",
        lambda m: f"Eq(Symbol({m.group(1)!r}), ",
        src,
    )
    # Executing the export as it stands builds each long sum one `+` at a
    # time, which is quadratic in SymPy (minutes for chain-6). So execute the
    # declarations, then build each right-hand side as one Add of its
    # top-level terms.
    head, rest = src.split("\nequations = [\n", 1)
    body, tail = rest.split("\n]\n", 1)
    env: dict = {}
    exec(head, env)
    exec(tail.split("\nexpected = [", 1)[0] + "\n" + tail[tail.index("\nlabels = ") :], env)
    if not env["abbreviations"]:
        # No abbreviation to unfold by differentiating: build the results
        # directly on plain symbols (f(t) -> f__d0, f.diff(t, k) -> f__dk,
        # the names `to_plain_symbols` gives), which is much faster than
        # creating thousands of Derivative objects.
        for key, value in list(env.items()):
            if isinstance(value, AppliedUndef):
                env[key] = sp.Symbol(f"{value.func.__name__}__d0")
        env["_d"] = lambda s, k: sp.Symbol(f"{s.name[: -len('__d0')]}__d{k}")
        body = re.sub(r"(\w+)\.diff\(t\)", r"_d(\1, 1)", body)
        body = re.sub(r"(\w+)\.diff\(t, (\d+)\)", r"_d(\1, \2)", body)
    rhs = []
    for line in body.splitlines():
        m = re.fullmatch(r"\s*Eq\(Symbol\(.*?\), (.*)\),", line)
        if m is None:
            raise ValueError(f"hdot derive {name} --format sympy: unexpected line {line[:80]!r}")
        rhs.append(eval_sum(m.group(1), env))
    env["equations"] = [sp.Eq(sp.Symbol(lab), r) for lab, r in zip(env["labels"], rhs)]
    eqs = {lab: eq.rhs for lab, eq in zip(env["labels"], env["equations"])}
    return eqs, env["abbreviations"]


def eval_sum(text, env):
    """Evaluates a printed sum as one Add of its top-level terms."""
    text = text.strip()
    sign = 1
    # -(a + b + ...) around the whole expression
    while text.startswith("-(") and matching_paren(text, 1) == len(text) - 1:
        sign, text = -sign, text[2:-1].strip()
    terms, depth, startpos = [], 0, 0
    for i, ch in enumerate(text):
        if ch in "([":
            depth += 1
        elif ch in ")]":
            depth -= 1
        elif ch in "+-" and depth == 0 and i > 0 and text[i - 1] == " ":
            terms.append(text[startpos:i])
            startpos = i
    terms.append(text[startpos:])
    values = [eval(t.replace(" ", "") or "0", env) for t in terms]  # noqa: S307 - our own export
    return sign * sp.Add(*values)


def matching_paren(text, open_at):
    """Index of the parenthesis closing the one at `open_at`."""
    depth = 0
    for i in range(open_at, len(text)):
        depth += {"(": 1, ")": -1}.get(text[i], 0)
        if depth == 0:
            return i
    return -1


def deep_call(fn):
    """Runs `fn` on a thread with a 1 GiB stack and a recursion limit of 10^6
    (re-raising its exception)."""
    err = []

    def target():
        try:
            fn()
        except BaseException as e:  # noqa: BLE001 - re-raised below
            err.append(e)

    old_limit, old_size = sys.getrecursionlimit(), threading.stack_size()
    sys.setrecursionlimit(1_000_000)
    threading.stack_size(1 << 30)
    try:
        th = threading.Thread(target=target)
        th.start()
        th.join()
    finally:
        threading.stack_size(old_size)
        sys.setrecursionlimit(old_limit)
    if err:
        raise err[0]


def hdot_terms(doc, step):
    """Number of terms of a step's components in hdot's canonical form."""
    for s in doc["steps"]:
        if s["name"] == step:
            return sum(c["terms"] for c in s["components"])
    raise KeyError(step)


def criterion_median(crit_dir, group, bench, param=None):
    """Median (seconds) of a criterion benchmark, or None."""
    if crit_dir is None:
        return None
    p = Path(crit_dir) / group / bench
    if param is not None:
        p = p / str(param)
    # criterion replaces '+' in directory names; try both spellings
    candidates = [p, Path(str(p).replace("+", "_"))]
    for c in candidates:
        f = c / "new" / "estimates.json"
        if f.exists():
            return json.loads(f.read_text())["median"]["point_estimate"] * 1e-9
    return None


# --------------------------------------------------------------------------
# Numeric comparison
# --------------------------------------------------------------------------


def to_plain_symbols(expr):
    """Replaces f(t)^(k) by a symbol per (f, k), so that numbers can be
    substituted consistently into both results."""
    reps = {}
    for d in expr.atoms(sp.Derivative):
        f = d.expr
        reps[d] = sp.Symbol(f"{f.func.__name__}__d{d.derivative_count}")
    expr = expr.xreplace(reps)
    reps = {f: sp.Symbol(f"{f.func.__name__}__d0") for f in expr.atoms(AppliedUndef)}
    return expr.xreplace(reps)


def agree(pairs, seed, points=3):
    """True when every (hdot, sympy, sympy_expanded) triple is equal at
    `points` seeded random points. The tolerance scales with the size of the
    terms: 64 eps times the sum of the absolute values of the terms of the
    expanded SymPy result (the rounding error of evaluating either form)."""
    plain = [tuple(to_plain_symbols(e) for e in triple) for triple in pairs]
    names = sorted({s.name for tr in plain for e in tr for s in e.free_symbols})
    syms = [sp.Symbol(n) for n in names]
    fns = []
    for a, b, expanded in plain:
        terms = sp.Add.make_args(expanded)
        scale = sp.Add(*[sp.Abs(x) for x in terms], evaluate=False)
        fns.append(tuple(sp.lambdify(syms, e, modules="math") for e in (a, b, scale)))
    worst = 0.0
    for p in range(points):
        rng = random.Random(seed * 1000 + p)
        vals = []
        for n in names:
            # inertia symbols in [0.5, 2]; angles and rates in [-1.5, 1.5]
            vals.append(rng.uniform(0.5, 2.0) if n.startswith("I") else rng.uniform(-1.5, 1.5))
        for fa, fb, fs in fns:
            a, b, s = fa(*vals), fb(*vals), fs(*vals)
            tol = 64 * sys.float_info.epsilon * max(s, 1.0)
            worst = max(worst, abs(a - b) / tol)
            if abs(a - b) > tol:
                return False, worst
    return True, worst


def unfold(expr, abbreviations):
    """Replaces hdot's abbreviations (omega_z) by what they stand for."""
    if not abbreviations:
        return expr
    return expr.subs(abbreviations).doit()


# --------------------------------------------------------------------------


def time_sympy(fn, *args, budget=3.0, max_runs=3):
    """Best wall time of `fn(*args)` with a cold SymPy cache; repeats (up to
    `max_runs`) only while the total stays under `budget` seconds."""
    best, total, runs, result = math.inf, 0.0, 0, None
    while runs < max_runs and (runs == 0 or total + best < budget):
        clear_cache()
        t0 = time.perf_counter()
        result = fn(*args)
        dt = time.perf_counter() - t0
        best, total, runs = min(best, dt), total + dt, runs + 1
    return best, runs, result


def fmt_time(s):
    if s is None:
        return "—"
    if s < 1e-3:
        return f"{s * 1e6:.0f} µs"
    if s < 1:
        return f"{s * 1e3:.2f} ms"
    return f"{s:.2f} s"


def fmt_ratio(a, b):
    if a is None or b is None:
        return "—"
    return f"{b / a:,.0f}×"


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    target = os.environ.get("CARGO_TARGET_DIR", str(ROOT / "target"))
    ap.add_argument("--max-k", type=int, default=6, help="largest K of chain-K (default 6)")
    ap.add_argument("--hdot", default=str(Path(target) / "release" / "hdot"),
                    help="the hdot release binary (default $CARGO_TARGET_DIR/release/hdot)")
    ap.add_argument("--criterion", default=str(Path(target) / "criterion"),
                    help="criterion results of `cargo bench -p hdot-sym --bench derive`")
    ap.add_argument("--runs", type=int, default=7, help="hdot runs per workload (best is kept)")
    ap.add_argument("--seed", type=int, default=3, help="seed of the random check points")
    ap.add_argument("--csv", default=str(ROOT / "docs" / "perf" / "compare_sympy.csv"))
    ap.add_argument("--chart", default=str(ROOT / "docs" / "perf" / "chain-k"),
                    help="chart path without extension (.png and .svg are written)")
    ap.add_argument("--no-chart", action="store_true")
    args = ap.parse_args()

    exe = args.hdot
    if not Path(exe).exists():
        sys.exit(f"compare_sympy: {exe} not found; build it with `cargo build --release -p hdot` "
                 "or pass --hdot")
    crit = args.criterion if Path(args.criterion).is_dir() else None
    if crit is None:
        print(f"(no criterion results in {args.criterion}: only process times for hdot)")

    print(f"sympy {sp.__version__}, python {sys.version.split()[0]}, hdot {exe}")
    workloads = [
        # name, hdot derivation, hdot step, criterion (group, bench, param), sympy fn, args
        ("euler-general", "euler-general", "M", ("file", "euler-general", None), sympy_euler_general, ()),
        ("gyroscope", "gyroscope", "M", ("file", "gyroscope", None), sympy_gyroscope, ()),
    ]
    for k in range(1, args.max_k + 1):
        workloads.append((f"chain-{k}", f"chain-{k}", "Hdot", ("chain", "derive+print", k), sympy_chain, (k,)))

    rows = []
    header = ["workload", "hdot process (s)", "hdot criterion median (s)", "sympy (s)",
              "sympy runs", "ratio process", "ratio criterion", "terms hdot", "terms sympy",
              "agree", "check points"]
    print(f"\n{'workload':<14} {'hdot proc':>10} {'hdot crit':>10} {'sympy':>9} "
          f"{'ratio':>8} {'ratio crit':>10} {'terms hdot':>10} {'terms sympy':>11}  agree")
    for name, hname, step, (g, b, prm), fn, fargs in workloads:
        t_proc, doc = hdot_time(exe, hname, args.runs)
        t_crit = criterion_median(crit, g, b, prm)
        eqs, abbrevs = hdot_equations(exe, hname)
        t_sym, runs, (comps, expanded, sym_abbrevs) = time_sympy(fn, *fargs)
        hd = [unfold(eqs[f"{step}.{c}"], abbrevs) for c in "xyz"]
        comps = [unfold(c, sym_abbrevs) for c in comps]
        verdict = []
        deep_call(lambda: verdict.append(agree(list(zip(hd, comps, expanded)), args.seed)))
        ok, worst = verdict[0]
        terms_h = hdot_terms(doc, step)
        terms_s = sum(len(sp.Add.make_args(e)) for e in expanded)
        rows.append([name, t_proc, t_crit, t_sym, runs,
                     t_sym / t_proc, (t_sym / t_crit) if t_crit else None,
                     terms_h, terms_s, "yes" if ok else "NO", 3])
        print(f"{name:<14} {fmt_time(t_proc):>10} {fmt_time(t_crit):>10} {fmt_time(t_sym):>9} "
              f"{fmt_ratio(t_proc, t_sym):>8} {fmt_ratio(t_crit, t_sym):>10} "
              f"{terms_h:>10,} {terms_s:>11,}  {'yes' if ok else 'NO'} "
              f"(worst |Δ|/tol {worst:.2g})", flush=True)

    print("\nhdot process = best wall time of `hdot derive NAME --format json` "
          f"over {args.runs} runs (includes process start-up);")
    print("hdot criterion = median of `cargo bench -p hdot-sym --bench derive` "
          "(file/NAME: parse+derive+check+print; chain/derive+print/K);")
    print("sympy = best of up to 3 runs with a cold cache (1 run when a run exceeds ~1.5 s);")
    print("terms = terms of the result's three components after expansion "
          "(hdot: its canonical form, sin² → 1 − cos²; sympy: expand(), no trig reduction).")
    print("euler-general/gyroscope: hdot runs the whole file (every step and check), sympy only M.")

    Path(args.csv).parent.mkdir(parents=True, exist_ok=True)
    with open(args.csv, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(header)
        for r in rows:
            w.writerow([r[0]] + [("" if v is None else (f"{v:.6g}" if isinstance(v, float) else v))
                                 for v in r[1:]])
    print(f"wrote {os.path.relpath(args.csv)}")

    if not args.no_chart:
        chart(rows, args.chart)
    if any(r[9] != "yes" for r in rows):
        sys.exit("compare_sympy: hdot and sympy disagree on some workload")


def chart(rows, stem):
    try:
        import matplotlib
    except ImportError:
        print("installing matplotlib (pip install --quiet matplotlib) for the chart")
        subprocess.run([sys.executable, "-m", "pip", "install", "--quiet", "matplotlib"], check=True)
        import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    chain = [r for r in rows if r[0].startswith("chain-")]
    ks = [int(r[0].split("-")[1]) for r in chain]
    fig, (ax, ax2) = plt.subplots(1, 2, figsize=(10, 4.2))
    ax.semilogy(ks, [r[3] for r in chain], "o-", label="sympy.physics.mechanics")
    ax.semilogy(ks, [r[1] for r in chain], "s-", label="hdot (process, best of runs)")
    if all(r[2] for r in chain):
        ax.semilogy(ks, [r[2] for r in chain], "^--", label="hdot (criterion median, in process)")
    ax.set_xlabel("K (bodies in the chain)")
    ax.set_ylabel("time (s)")
    ax.set_title("chain-K: Ḣ in N, expanded")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    ax2.loglog([r[8] for r in chain], [r[3] for r in chain], "o-", label="sympy (terms of expand())")
    ax2.loglog([r[7] for r in chain], [r[1] for r in chain], "s-", label="hdot process (canonical terms)")
    if all(r[2] for r in chain):
        ax2.loglog([r[7] for r in chain], [r[2] for r in chain], "^--", label="hdot criterion")
    ax2.set_xlabel("terms in the result")
    ax2.set_ylabel("time (s)")
    ax2.set_title("time against size of the result")
    ax2.grid(True, which="both", alpha=0.3)
    ax2.legend(fontsize=8)
    fig.tight_layout()
    for ext in ("png", "svg"):
        fig.savefig(f"{stem}.{ext}", dpi=110)
        print(f"wrote {os.path.relpath(stem)}.{ext}")


if __name__ == "__main__":
    main()
