#!/usr/bin/env python3
"""Articulated chains: inertance's system impact against Pinocchio's ``impulseDynamics``.

The planar chain of ``src/tools/chain.rs`` (N bars of length 1 and mass 1 along +x, hinges
about z, the first to the ground at the origin, turning as one bar at omega = -1 about z and
striking the ground y = 0 with the tip and the far end of the middle bar, k = 1/2; N = 1 keeps
the tip only) is built as a Pinocchio model with N revolute-z joints and the same masses,
centres and inertias.  For each N:

  * inertance: ``cargo run --release --example chain_timing -- N ...`` prints, per N, the
    in-process time of one solve from the chain's data (``System::new`` with the joints' articulated-body
    factorization, ``Impact::assemble``, Newton's law, every output; median over 7 runs of the
    mean per call, each run >= 20 ms) and the answer (impulses, each link's omega_z);
  * Pinocchio, with the two contacts' normal rows of the frame Jacobians (taken outside the
    timing): ``impulseDynamics(model, data, q, v, J, e, 0)`` (crba + Cholesky of M and of
    J M^-1 J^T + solve: Newton's law with one coefficient) timed the same way (timeit, gc off),
    and the whole Pinocchio path with the Jacobians (computeJointJacobians + getFrameJacobian);
  * Pinocchio's same call **from C++** (pinocchio_chain.cpp, no Python between the clock and the
    call): the same model (written by ``model.saveToBinary``), q, v and J, timed as inertance is;
    built once with g++ against the ``pin`` wheel (pin_build.py, as compare.py's harness), when
    g++ and the cmeel prefix with Eigen's headers (``cmeel-eigen``) are there (``--no-cxx`` skips
    it).  Its answers must equal the Python call's to a few ulps (the same library).

Agreement: both Newton impulses are compressive in every scene (checked: the bilateral law is
then the unilateral one, the problem Pinocchio solves), and the joint rates after impact agree:
inertance's link rates omega_i give qdot_i = omega_i - omega_{i-1}; the difference is reported
as max |qdot_pin - qdot_inertance| / max |qdot| and must stay below 16 N^4 eps (see rtol() and
chains.md for why that tolerance).  Not part of CI.

Run:  python3 -m venv target/peers-venv && target/peers-venv/bin/pip install pin numpy cmeel-eigen
      target/peers-venv/bin/python benches/peers/chains.py [--sizes 1 10 100 1000]
"""

from __future__ import annotations

import argparse
import datetime
import gc
import json
import os
import platform
import statistics
import subprocess
import sys
import tempfile
import timeit
from pathlib import Path

import numpy as np
import pinocchio as pin

import pin_build  # benches/peers/pin_build.py: the C++ harness's build, shared with compare.py

REPO = Path(__file__).resolve().parents[2]

# Agreement of the joint rates after impact, relative to the largest rate: both solves are
# backward stable, so they differ by about cond * eps, and the conditioning of an N-link chain's
# impact grows like N^4 (its reduced mass matrix, like a discretised string's stiffness, spans
# N^2 between its slowest and fastest modes, and the rates are read through it twice: N^4).
# The bound is 16 N^4 eps (see chains.md: observed 4e-16 at N = 1, 3e-8 at N = 300 under a bound
# of 3e-5); any convention error (a sign, a lever arm) gives differences of order 1.


def rtol(n: int) -> float:
    return 16.0 * max(n, 1) ** 4 * np.finfo(float).eps


K = 0.5
JX = 1.0 / 1200.0
JZ = 1.0 / 12.0 + 1.0 / 1200.0


def pinocchio_chain(n: int):
    """The chain as a Pinocchio model: N revolute-z joints, joint i at x = i in the world (at
    (1, 0, 0) in its parent's frame), each bar's centre at (1/2, 0, 0) in its joint's frame."""
    model = pin.Model()
    parent = 0
    for i in range(n):
        placement = pin.SE3(np.eye(3), np.array([0.0 if i == 0 else 1.0, 0.0, 0.0]))
        jid = model.addJoint(parent, pin.JointModelRZ(), placement, f"hinge{i}")
        model.appendBodyToJoint(
            jid, pin.Inertia(1.0, np.array([0.5, 0.0, 0.0]), np.diag([JX, JZ, JZ])), pin.SE3.Identity()
        )
        parent = jid
    # Contact points: the tip (x = 1 on the last bar), the far end of the middle bar.
    mid = (n - 1) // 2
    points = [n] + ([mid + 1] if n > 1 else [])
    frames = []
    for k, joint in enumerate(points):
        frames.append(model.addFrame(pin.Frame(f"contact{k}", joint, pin.SE3(np.eye(3), np.array([1.0, 0.0, 0.0])),
                                               pin.FrameType.OP_FRAME)))
    return model, frames


def jacobian(model, data, q, frames):
    """The contacts' normal rows n^T J_lin(A_i), n = (0, -1, 0) out of the bars."""
    pin.computeJointJacobians(model, data, q)
    pin.updateFramePlacements(model, data)
    normal = np.array([0.0, -1.0, 0.0])
    return np.vstack([normal @ pin.getFrameJacobian(model, data, f, pin.LOCAL_WORLD_ALIGNED)[:3] for f in frames])


def initial_state(model):
    """q = 0 (the chain along +x), v: the first joint at -1 (the chain turns as one bar)."""
    v = np.zeros(model.nv)
    v[0] = -1.0
    return pin.neutral(model), v


# The C++ call agrees with the Python call (the same library, the same inputs) to this many ulps of
# the largest component.
CXX_ULPS = 4


def pinocchio_cxx_runs(sizes) -> tuple[dict, str | None]:
    """Pinocchio's impulseDynamics timed in C++ (pinocchio_chain.cpp) on the chains of `sizes`:
    ({N: {"ns": ns per call, "ulps": its answer's distance to the Python call's}}, None), or
    ({}, why not).  Each model is written with saveToBinary and read back by the harness, with q, v
    and the Jacobian rows taken here; every Data is released before the harness runs."""
    target = Path(os.environ.get("CARGO_TARGET_DIR", REPO / "target"))
    binary, why = pin_build.pinocchio_binary(Path(__file__).with_name("pinocchio_chain.cpp"), target / "peers",
                                             ("boost_serialization",))
    if binary is None:
        return {}, why
    ref, lines = {}, [str(len(sizes))]
    with tempfile.TemporaryDirectory(prefix="inertance-chains-") as tmp:
        for n in sizes:
            model, frames = pinocchio_chain(n)
            data = model.createData()
            q, v = initial_state(model)
            J = jacobian(model, data, q, frames)
            ref[n] = (pin.impulseDynamics(model, data, q, v, J, K, 0.0).copy(), data.impulse_c.copy())
            del data
            path = Path(tmp) / f"chain-{n}.bin"
            model.saveToBinary(str(path))
            lines += [str(path), f"{J.shape[0]} {K!r}",
                      *(" ".join(map(repr, x.ravel().tolist())) for x in (q, v, J))]
        p = subprocess.run([str(binary)], input="\n".join(lines) + "\n", capture_output=True, text=True)
    if p.returncode != 0:
        return {}, f"pinocchio_chain failed (exit {p.returncode}): {p.stderr[-300:]}"
    out = {}
    for r in map(json.loads, p.stdout.splitlines()):
        dq, impulse = ref[r["links"]]
        ulps = max(float(np.max(np.abs(np.array(r[key]) - x)) / (np.finfo(float).eps * np.max(np.abs(x))))
                   for key, x in (("dq_after", dq), ("impulse", impulse)))
        out[r["links"]] = {"ns": r["ns_per_call"], "ulps": ulps}
    return out, None


def time_per_call(fn, repeat: int = 7, min_time: float = 0.02) -> float:
    """Median over `repeat` runs of the mean time per call, each run >= min_time s (gc off)."""
    fn()
    t = timeit.Timer(fn)
    number = 1
    while t.timeit(number) < min_time:
        number *= 2
    return statistics.median(t.repeat(repeat=repeat, number=number)) / number


def fmt(s: float) -> str:
    ns = s * 1e9
    if ns < 1e3:
        return f"{ns:.0f} ns"
    if ns < 1e6:
        return f"{ns / 1e3:.3g} µs"
    return f"{ns / 1e6:.3g} ms"


def inertance_runs(sizes, example: str | None) -> dict:
    if example:
        cmd = [example]
    else:
        subprocess.run(["cargo", "build", "--release", "--example", "chain_timing"], cwd=REPO, check=True)
        target = Path(os.environ.get("CARGO_TARGET_DIR", REPO / "target"))
        cmd = [str(target / "release" / "examples" / "chain_timing")]
    out = subprocess.run(cmd + [str(n) for n in sizes], check=True, capture_output=True, text=True).stdout
    return {r["links"]: r for r in map(json.loads, out.splitlines())}


def cxx_cols(c: dict | None, t_ours: float) -> str:
    """The table's columns "pin C++ call" and its ratio to inertance's time."""
    if c is None:
        return f"{'—':>13} {'—':>12}"
    t = c["ns"] * 1e-9
    return f"{fmt(t):>13} {t / t_ours:>11.2f}×"


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--sizes", type=int, nargs="+", default=[1, 10, 100, 300, 1000])
    ap.add_argument("--pin-max", type=int, default=300,
                    help="longest chain given to Pinocchio: its Data takes O(N^3) memory (2.1 GB at N = 300)")
    ap.add_argument("--example", help="a built chain_timing binary (default: cargo builds it)")
    ap.add_argument("--repeat", type=int, default=7)
    ap.add_argument("--min-time", type=float, default=0.02)
    ap.add_argument("--no-cxx", dest="cxx", action="store_false",
                    help="skip Pinocchio's call timed in C++ (pinocchio_chain.cpp, built with g++)")
    args = ap.parse_args()

    print(f"chains: inertance vs Pinocchio {pin.__version__} impulseDynamics, "
          f"{datetime.datetime.now(datetime.timezone.utc):%Y-%m-%d %H:%M} UTC, "
          f"{platform.python_implementation()} {platform.python_version()}, numpy {np.__version__}, "
          f"load {os.getloadavg()[0]:.1f}")
    ours = inertance_runs(args.sizes, args.example)
    cxx, cxx_why = pinocchio_cxx_runs([n for n in args.sizes if n <= args.pin_max]) if args.cxx else ({}, "--no-cxx")
    gc.disable()
    rows, ok, lean_rows = [], True, {}
    for n in args.sizes:
        r = ours[n]
        if n > args.pin_max:
            rows.append((n, r["ns_per_solve"] * 1e-9, None, None, None, None, np.array(r["impulses"]), None))
            continue
        model, frames = pinocchio_chain(n)
        data = model.createData()
        q, v = initial_state(model)
        J = jacobian(model, data, q, frames)
        dq = pin.impulseDynamics(model, data, q, v, J, K, 0.0).copy()
        impulse = -data.impulse_c.copy()  # Pinocchio's lambda = -P
        omega = np.array(r["omega_z"])
        qdot = np.diff(np.concatenate([[0.0], omega]))
        agree = float(np.max(np.abs(dq - qdot)) / np.max(np.abs(qdot)))
        p_agree = float(np.max(np.abs(impulse - np.array(r["impulses"]))) / np.max(np.abs(impulse)))
        compressive = bool(np.all(impulse > 0))
        ok &= agree <= rtol(n) and p_agree <= rtol(n) and compressive

        t_call = time_per_call(lambda: pin.impulseDynamics(model, data, q, v, J, K, 0.0), args.repeat, args.min_time)
        t_path = time_per_call(lambda: pin.impulseDynamics(model, data, q, v, jacobian(model, data, q, frames), K, 0.0),
                               args.repeat, args.min_time)
        t_ours = r["ns_per_solve"] * 1e-9
        rows.append((n, t_ours, t_call, t_path, agree, p_agree, impulse, compressive))
        # The lean path (impact::lean_system): its answer against Pinocchio's too.
        lean_qdot = np.diff(np.concatenate([[0.0], np.array(r["lean_omega_z"])]))
        lean_agree = max(float(np.max(np.abs(dq - lean_qdot)) / np.max(np.abs(lean_qdot))),
                         float(np.max(np.abs(impulse - np.array(r["lean_impulses"]))) / np.max(np.abs(impulse))))
        ok &= lean_agree <= rtol(n)
        lean_rows[n] = (t_call, lean_agree)
    gc.enable()

    print(f"\n{'N':>6} {'inertance':>11} {'per body':>10} {'pin call':>11} {'÷ inertance':>12} "
          f"{'pin +Jacobians':>15} {'÷ inertance':>12} {'pin C++ call':>13} {'÷ inertance':>12}  "
          f"{'qdot agree':>10} {'P agree':>9}  impulses (Newton)")
    for n, t_ours, t_call, t_path, agree, p_agree, impulse, compressive in rows:
        if t_call is None:
            print(f"{n:>6} {fmt(t_ours):>11} {fmt(t_ours / n):>10} {'—':>11} {'—':>12} {'—':>15} {'—':>12} "
                  f"{'—':>13} {'—':>12}  "
                  f"{'—':>10} {'—':>9}  {', '.join(f'{p:.6g}' for p in impulse)}  (Pinocchio not run: "
                  f"its Data for {n} joints would take ~{2.1 * (n / 300) ** 3:.0f} GB)")
            continue
        print(f"{n:>6} {fmt(t_ours):>11} {fmt(t_ours / n):>10} {fmt(t_call):>11} {t_call / t_ours:>11.2f}× "
              f"{fmt(t_path):>15} {t_path / t_ours:>11.2f}× {cxx_cols(cxx.get(n), t_ours)}  "
              f"{agree:>10.1e} {p_agree:>9.1e}  "
              f"{', '.join(f'{p:.6g}' for p in impulse)}{'' if compressive else '  (NOT compressive)'}")
    print(f"\nThe lean path (impact::lean_system: the system built once, as Pinocchio's model and data "
          f"are; per call the articulated factorization, the responses, the basis, Newton's law; "
          f"impulses and twist only):\n")
    print(f"{'N':>6} {'lean':>11} {'per body':>10} {'pin C++ call':>13} {'÷ lean':>8} {'pin call':>11} "
          f"{'÷ lean':>8}  {'agree':>8}")
    for n in args.sizes:
        t_lean = ours[n]["ns_per_solve_lean"] * 1e-9
        t_call, lean_agree = lean_rows.get(n, (None, None))
        c = cxx.get(n)
        t_cxx = c["ns"] * 1e-9 if c else None
        col = lambda t: (f"{fmt(t):>13}", f"{t / t_lean:>7.2f}×") if t else (f"{'—':>13}", f"{'—':>8}")
        cx, cr = col(t_cxx)
        px, pr = col(t_call)
        print(f"{n:>6} {fmt(t_lean):>11} {fmt(t_lean / n):>10} {cx} {cr} {px[2:]} {pr}  "
              f"{'—' if lean_agree is None else f'{lean_agree:.1e}':>8}")
    if cxx:
        worst = max(c["ulps"] for c in cxx.values())
        ok &= worst <= CXX_ULPS
        print(f"\npin C++ call (pinocchio_chain.cpp): dq_after and impulses within {worst:.3g} ulps of the "
              f"Python call's (bound {CXX_ULPS})" + ("" if worst <= CXX_ULPS else "  MISMATCH"))
    else:
        print(f"\npin C++ call not run: {cxx_why}")
    print("\nagreement:", "every chain agrees with inertance" if ok else "MISMATCH")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
