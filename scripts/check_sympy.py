#!/usr/bin/env python3
"""SymPy round trip of every derivation.

For each derivation file, runs `hdot derive NAME --format sympy`, executes the
generated Python, and checks with sympy that

  1. every equation equals the derivation's own expected (textbook) form, once
     abbreviations are expanded (``simplify(rhs - expected) == 0``);
  2. the main results equal the textbook forms of docs/equations.md, written
     here independently in sympy (sections 1, 5 and 6);
  3. where a file exports both solved accelerations and a mass-matrix form,
     M.LUsolve(f) equals the accelerations;
  4. every matrix, array and list of the JSON export (`hdot derive NAME
     --format json`, a step's `value.rows`: an array of rows in source
     syntax) equals, entry by entry, the SymPy export's equations of that
     step and, for an array or a list, its `Matrix` of the same shape.
     An entry of more than SYMBOLIC_UP_TO terms (the nonlinear bicycle's
     mass matrix, forcing and constraint rates, up to 3,213 terms, on which
     sympy's simplify takes minutes) is compared numerically instead: both
     sides evaluated by lambdify at NUMERIC_POINTS seeded random values of
     every symbol, coordinate and rate, equal to 1e-9 of their magnitude.

Usage: scripts/check_sympy.py [path/to/hdot] [NAME ...]
Exit status: 0 when everything holds, 1 otherwise.
"""

import json
import math
import pathlib
import random
import re
import subprocess
import sys

import sympy
from sympy import Function, Symbol, cos, simplify, sin

ROOT = pathlib.Path(__file__).resolve().parent.parent


def export(hdot, name):
    out = subprocess.run([hdot, "derive", name, "--format", "sympy"], cwd=ROOT,
                         capture_output=True, text=True)
    if out.returncode != 0:
        raise SystemExit(f"hdot derive {name} failed ({out.returncode}):\n{out.stderr}")
    ns = {}
    exec(compile(out.stdout, f"<{name} sympy export>", "exec"), ns)
    return ns


def json_export(hdot, name):
    out = subprocess.run([hdot, "derive", name, "--format", "json"], cwd=ROOT,
                         capture_output=True, text=True)
    if out.returncode != 0:
        raise SystemExit(f"hdot derive {name} --format json failed ({out.returncode}):\n{out.stderr}")
    return json.loads(out.stdout)


# A name with its primes, an integer, `^`, or any other character.
TOKEN = re.compile(r"([A-Za-z_][A-Za-z0-9_]*)('*)|([0-9]+)|(\^)|(.)", re.S)


def symbol_table(ns):
    """The SymPy objects of an export by the names of the derivation file:
    a constant is Symbol(name), a function of time Function(name)(t)."""
    table = {}
    for v in ns.values():
        if isinstance(v, sympy.Symbol):
            table[v.name] = v
        elif isinstance(v, sympy.core.function.AppliedUndef):
            table[v.func.__name__] = v
    return table


def from_source(text, table):
    """An expression in hdot's source syntax (`I_x*omega_x' - sin(theta)^2`,
    `1/2*m`) as SymPy: names looked up in `table`, primes as derivatives in
    t, integers exact (so `1/2` is a Rational)."""
    out = []
    for name, primes, num, caret, other in TOKEN.findall(text):
        if name in ("sin", "cos") and not primes:
            out.append(name)
        elif name:
            if name not in table:
                raise ValueError(f"unknown name {name!r} in {text!r}")
            out.append(f"S[{name!r}]" + (f".diff(t, {len(primes)})" if primes else ""))
        elif num:
            out.append(f"Integer({num})")
        elif caret:
            out.append("**")
        else:
            out.append(other)
    scope = {"__builtins__": {}, "S": table, "sin": sin, "cos": cos,
             "Integer": sympy.Integer, "t": Symbol("t")}
    # A sum is evaluated term by term: Python's compiler cannot take a sum
    # of thousands of terms in one expression.
    terms, depth, previous = [[]], 0, None
    for token in out:
        if token.strip() == "":
            continue
        if token == "(":
            depth += 1
        elif token == ")":
            depth -= 1
        elif depth == 0 and token in "+-" and previous not in (None, "+", "-", "*", "/", "**", "("):
            terms.append([])
        terms[-1].append(token)
        previous = token
    return sympy.Add(*(eval("".join(t), scope) for t in terms))


def step_matrix(ns, name, shape):
    """The export's Matrix of step `name` (`K`, or `K_` when the name was
    taken by a symbol) with the given shape, or None."""
    v = name
    while v in ns:
        if isinstance(ns[v], sympy.MatrixBase) and ns[v].shape == shape:
            return ns[v]
        v += "_"
    return None


# Entries with more terms than this are compared numerically (see 4. above).
SYMBOLIC_UP_TO = 200
NUMERIC_POINTS = 2


def equal(a, b, abbreviations):
    """a == b: symbolically, or numerically for an entry of more than
    SYMBOLIC_UP_TO terms."""
    if max(len(sympy.Add.make_args(a)), len(sympy.Add.make_args(b))) <= SYMBOLIC_UP_TO:
        return is_zero(a - b, abbreviations)
    return numerically_equal(a, b, abbreviations)


def numerically_equal(a, b, abbreviations):
    """a == b at NUMERIC_POINTS seeded random values of every symbol and
    function of time (its rates as further symbols), to 1e-9 of the
    magnitude of the terms."""
    if abbreviations:
        a, b = a.subs(abbreviations).doit(), b.subs(abbreviations).doit()
    # Rates first (a rate holds its coordinate), highest order first.
    derivatives = sorted((a.atoms(sympy.Derivative) | b.atoms(sympy.Derivative)),
                         key=lambda d: (-d.derivative_count, str(d)))
    names = {d: Symbol(f"_rate{k}") for k, d in enumerate(derivatives)}
    a, b = a.xreplace(names), b.xreplace(names)
    functions = sorted(a.atoms(sympy.core.function.AppliedUndef)
                       | b.atoms(sympy.core.function.AppliedUndef), key=str)
    names = {f: Symbol(f"_coordinate{k}") for k, f in enumerate(functions)}
    a, b = a.xreplace(names), b.xreplace(names)
    symbols = sorted(a.free_symbols | b.free_symbols, key=str)
    # Each side as the list of its terms (Python cannot compile a sum of
    # thousands of terms as one expression), added by fsum.
    fa, fb = (sympy.lambdify(symbols, list(sympy.Add.make_args(e)), "math") for e in (a, b))
    rng = random.Random(20261127)
    for _ in range(NUMERIC_POINTS):
        values = [rng.uniform(0.5, 1.5) for _ in symbols]
        ta, tb = fa(*values), fb(*values)
        # The magnitude: the sum of the terms' absolute values.
        scale = max(1.0, math.fsum(abs(x) for x in ta), math.fsum(abs(x) for x in tb))
        if not math.isclose(math.fsum(ta), math.fsum(tb), rel_tol=0, abs_tol=1e-9 * scale):
            return False
    return True


def compare_matrices(step, rows, equations, matrix, table, abbreviations):
    """The failures (messages) among a step's JSON rows against its SymPy
    equations (flattened in row order) and, when given, its Matrix."""
    failures = []
    flat = [from_source(e, table) for r in rows for e in r]
    if len(flat) != len(equations):
        return [f"{step}: {len(flat)} JSON entries, {len(equations)} SymPy equations"]
    for k, (a, eq) in enumerate(zip(flat, equations)):
        if not equal(a, eq.rhs, abbreviations):
            failures.append(f"{step}[{k}]: JSON {a} != SymPy {eq.rhs}")
    if matrix is not None:
        for i, r in enumerate(rows):
            for j, _ in enumerate(r):
                if not equal(flat[i * len(r) + j], matrix[i, j], abbreviations):
                    failures.append(f"{step}[{i + 1},{j + 1}]: JSON {rows[i][j]} != Matrix {matrix[i, j]}")
    return failures


def is_zero(expr, abbreviations):
    e = expr.subs(abbreviations).doit() if abbreviations else expr
    return simplify(sympy.expand(e)) == 0 or simplify(sympy.trigsimp(e)) == 0


def textbook():
    """Independent textbook forms, keyed by (derivation, step.component)."""
    t = Symbol("t")
    Ix, Iy, Iz = Symbol("I_x"), Symbol("I_y"), Symbol("I_z")
    Ixy, Iyz, Izx = Symbol("I_xy"), Symbol("I_yz"), Symbol("I_zx")
    wx, wy, wz = (Function(n)(t) for n in ("omega_x", "omega_y", "omega_z"))
    w = Function("omega")(t)
    ph, th, ps = (Function(n)(t) for n in ("phi", "theta", "psi"))
    I, Ip, m, g, l = (Symbol(n) for n in ("I", "Ip", "m", "g", "l"))
    a = w.diff(t)
    d = lambda f: f.diff(t)  # noqa: E731
    return {
        ("euler-principal", "M.x"): Ix * d(wx) - (Iy - Iz) * wy * wz,
        ("euler-principal", "M.y"): Iy * d(wy) - (Iz - Ix) * wz * wx,
        ("euler-principal", "M.z"): Iz * d(wz) - (Ix - Iy) * wx * wy,
        ("angular-momentum", "H.x"): Ix * wx - Ixy * wy - Izx * wz,
        ("angular-momentum", "H.y"): -Ixy * wx + Iy * wy - Iyz * wz,
        ("angular-momentum", "H.z"): -Izx * wx - Iyz * wy + Iz * wz,
        ("fixed-axis", "M.x"): -Izx * a + Iyz * w**2,
        ("fixed-axis", "M.y"): -Iyz * a - Izx * w**2,
        ("fixed-axis", "M.z"): Iz * a,
        # Section 5's general form from section 1: M = dH/dt + w x H.
        ("euler-general", "M_principal.x"): Ix * d(wx) - (Iy - Iz) * wy * wz,
        # The heavy top from its Lagrangian (Goldstein §5.7), written out here:
        # I' θ'' = I' φ'² sin θ cos θ − I ω_z φ' sin θ + m g l sin θ.
        ("heavy-top", "accelerations.theta''"): (
            Ip * d(ph)**2 * sin(th) * cos(th) - I * (d(ps) + d(ph) * cos(th)) * d(ph) * sin(th)
            + m * g * l * sin(th)) / Ip,
        ("heavy-top", "accelerations_lagrange.theta''"): (
            Ip * d(ph)**2 * sin(th) * cos(th) - I * (d(ps) + d(ph) * cos(th)) * d(ph) * sin(th)
            + m * g * l * sin(th)) / Ip,
    }


def main():
    hdot = sys.argv[1] if len(sys.argv) > 1 else str(ROOT / "target/release/hdot")
    names = sys.argv[2:] or sorted(
        p.stem for p in (ROOT / "derivations").glob("*.toml") if p.name != "notes.toml"
    )
    book = textbook()
    failures = 0
    checked = 0
    for name in names:
        ns = export(hdot, name)
        abbreviations = ns["abbreviations"]
        for eq, exp, label in zip(ns["equations"], ns["expected"], ns["labels"]):
            if exp is not None:
                checked += 1
                if eq.lhs != exp.lhs or not is_zero(eq.rhs - exp.rhs, abbreviations):
                    failures += 1
                    print(f"FAIL {name} {label}: {eq.rhs} != {exp.rhs}")
            ref = book.get((name, label))
            if ref is not None:
                checked += 1
                if not is_zero(eq.rhs.subs(abbreviations).doit() - ref, {}):
                    failures += 1
                    print(f"FAIL {name} {label}: {eq.rhs} != textbook {ref}")
        # Equations of motion exported both ways: M.LUsolve(f) must give the
        # solved accelerations, so a sympy user can continue from either.
        m, f = ns.get("mass_matrix"), ns.get("forcing")
        if isinstance(m, sympy.MatrixBase) and isinstance(f, sympy.MatrixBase):
            for key, solved in ns.items():
                if not (isinstance(solved, dict) and len(solved) == m.rows
                        and all(isinstance(k, sympy.Derivative) for k in solved)):
                    continue
                qdd = m.LUsolve(f)
                for k, (q, value) in enumerate(solved.items()):
                    checked += 1
                    if not is_zero(qdd[k] - value, abbreviations):
                        failures += 1
                        print(f"FAIL {name} {key}: M⁻¹f gives {qdd[k]} for {q}, the export {value}")
        # Matrices of the JSON export, entry by entry.
        table = symbol_table(ns)
        for step in json_export(hdot, name)["steps"]:
            rows = step["value"].get("rows")
            if not step["show"] or rows is None:
                continue
            prefix = step["name"] + "."
            eqs = [eq for eq, label in zip(ns["equations"], ns["labels"]) if label.startswith(prefix)]
            shape = (len(rows), len(rows[0]) if rows else 0)
            matrix = step_matrix(ns, step["name"], shape) if step["value"]["kind"] != "matrix" else None
            checked += 1
            for msg in compare_matrices(step["name"], rows, eqs, matrix, table, abbreviations):
                failures += 1
                print(f"FAIL {name} {msg}")
        print(f"ok   {name}: {len(ns['equations'])} equations rebuilt by sympy {sympy.__version__}")
    print(f"sympy: {checked} comparisons, {failures} failed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
