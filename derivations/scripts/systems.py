"""Systems of bodies in one impact: the closed forms of derivations/systems.md, derived here
without the program (SymPy, exact rationals).

Run: python3 derivations/scripts/systems.py   (needs sympy)

1. Newton's cradle of n = 3, 4, 5 equal balls: G = tridiag(-1, 2, -1)/m, the simultaneous
   Newton and Poisson laws and both in inequality form, symbolically in m, v, k; and the
   sequence of binary collisions that the experiment follows.
2. The box landing on a box on the floor (examples/box-on-box.toml): the rebound off the
   lowest edge, the floor's least-norm impulses.
3. The double pendulum striking a wall (examples/double-pendulum-wall.toml) and the
   three-link leg landing on heel and toe (examples/leg-heel-toe.toml), in joint coordinates:
   M(q) = sum over links of m Jv^T Jv + J Jw^T Jw, J_c = n . dA/dq, the laws on
   G = J_c M^-1 J_c^T, q' after = q' before - M^-1 J_c^T P.

Each part prints what derivations/systems.md quotes; tests/system_validation.rs checks the
program against the same formulas written a second time, in Rust.
"""

from itertools import product as cartesian

import sympy as sp

R = sp.Rational


# --- 1. Newton's cradle -----------------------------------------------------------------------

m, v, k = sp.symbols("m v k", positive=True)


def cradle(n):
    N = n - 1
    G = sp.Matrix(N, N, lambda i, j: 2 if i == j else (-1 if abs(i - j) == 1 else 0)) / m
    v0 = sp.Matrix([v] + [0] * (N - 1))
    # Newton (eq. 15): G P = (1 + k) v0.  Poisson (eq. 21-23): G Pc = v0, P = (1 + k) Pc.
    newton = sp.simplify(G.solve((1 + k) * v0))
    pc = sp.simplify(G.solve(v0))
    poisson = sp.simplify((1 + k) * pc)
    assert sp.simplify(newton - poisson) == sp.zeros(N, 1)
    closed = sp.Matrix([(1 + k) * m * v * (n - i) / n for i in range(1, n)])
    assert sp.simplify(newton - closed) == sp.zeros(N, 1)
    # Each ball's velocity: the striker loses P1/m, ball j gains (P_{j-1} - P_j)/m.
    P = list(newton) + [0]
    speeds = [sp.factor(v - P[0] / m)] + [sp.factor((P[j - 1] - P[j]) / m) for j in range(1, n)]
    assert sp.simplify(speeds[0] - (1 - (n - 1) * k) * v / n) == 0
    assert all(sp.simplify(s - (1 + k) * v / n) == 0 for s in speeds[1:])
    # Unilateral Newton: q = v0 + k max(v0, 0) = (1 + k) v0 (the resting contacts have v0 = 0);
    # P > 0 with w = G P - q = 0 solves the LCP, and G is regular: the only solution.
    # Unilateral Poisson: compression Pc > 0 with w = 0; expansion from (1 + k) Pc has
    # G (1 + k) Pc - v0 = k v0 >= 0, so X = 0.
    assert all(p.subs({k: 0}) > 0 for p in pc.subs({m: 1, v: 1}))
    Ep = sp.factor(sum(m * (s - s0) ** 2 for s, s0 in zip(speeds, [v] + [0] * N)) / 2)
    dEc = sp.factor(m * v**2 / 2 - sum(m * s**2 for s in speeds) / 2)
    assert sp.simplify(Ep - m * (1 + k) ** 2 * v**2 * (n - 1) / (2 * n)) == 0
    assert sp.simplify(dEc - m * v**2 * (1 - k**2) * (n - 1) / (2 * n)) == 0
    return list(newton), list(pc), speeds, Ep, dEc


def binary_sequence(n, kk):
    """The cradle as n - 1 binary collisions in turn, left to right, then again while some
    pair still approaches: equal masses u1, u2 -> ((1 - k)u1 + (1 + k)u2, (1 + k)u1 + (1 - k)u2)/2."""
    u = [R(1)] + [R(0)] * (n - 1)
    for _ in range(100 * n):
        pairs = [i for i in range(n - 1) if u[i] > u[i + 1]]
        if not pairs:
            return u
        i = pairs[0]
        a, b = u[i], u[i + 1]
        u[i] = ((1 - kk) * a + (1 + kk) * b) / 2
        u[i + 1] = ((1 + kk) * a + (1 - kk) * b) / 2
    raise RuntimeError("no end")


print("1. Newton's cradle: G = tridiag(-1, 2, -1)/m, striker at v, k at every contact")
for n in (3, 4, 5):
    P, Pc, speeds, Ep, dEc = cradle(n)
    print(f"  n = {n}: P = {[sp.factor(p) for p in P]}")
    print(f"         Pc = {Pc}")
    print(f"         speeds after = {speeds}")
    print(f"         E_p = {Ep}, dE_c = {dEc}")
    for kk in (R(0), R(1, 2), R(1)):
        print(f"         k = {kk}: {[s.subs({k: kk, v: 1}) for s in speeds]} v")
    print(f"         binary collisions in turn, k = 1: {binary_sequence(n, R(1))} v")
    print(f"         binary collisions in turn, k = 1/2: {binary_sequence(n, R(1, 2))} v")


# --- 2. A box landing on a box on the floor ---------------------------------------------------

print("\n2. Box on box (examples/box-on-box.toml)")
mt, kb, V = R(2), R(1, 2), R(1)
a, b, h = R(1, 5), R(1, 10), R(1, 20)
C, S = R(24, 25), R(7, 25)          # quaternion (7, 0, 1, 0): rotation about y
assert C**2 + S**2 == 1
# The top box's lowest corners, body (a, +-b, -h) -> world offset (C a - S h, +-b, -S a - C h).
d, drop = C * a - S * h, S * a + C * h
Jy = mt * (a**2 + h**2) / 3
Pt = (1 + kb) * V / (2 / mt + 2 * d**2 / Jy)
xc, A = R(-1, 10), R(3, 10)
X = xc + d
print(f"  lever arm d = {d}, corner drop {drop}, top centre z = 1/5 + {drop} = {R(1, 5) + drop}")
print(f"  J_y = {Jy}, P at each corner = {Pt}")
print(f"  top after: v_C = (1/2, 0, {-V + 2 * Pt / mt}), omega_y = {-2 * Pt * d / Jy}")
print(f"  floor, least norm (Newton): x = +A: {Pt / 2 * (1 + X / A)}, x = -A: {Pt / 2 * (1 - X / A)}"
      f"  (X = {X}, A = {A})")
Ep = mt * ((2 * Pt / mt) ** 2) / 2 + Jy * (2 * Pt * d / Jy) ** 2 / 2
print(f"  E_p = {Ep}, dE_c = E_p - ... = {sp.nsimplify(2 * Pt * V - Ep)} (eq. 34: -E_p + sum P v0)")


# --- 3. Planar chains in joint coordinates ------------------------------------------------

def chain_impact(links, free_base, rates, contacts, unilateral, model):
    """links: (mass, J, hinge o_l, centre); contacts: (link, point, normal, k)."""
    L = len(links)
    d = L + (2 if free_base else 0)

    def angle(l):
        return l + (2 if free_base else 0)

    def jv(j, p):
        cols = [sp.Matrix([0, 0]) for _ in range(d)]
        if free_base:
            cols[0], cols[1] = sp.Matrix([1, 0]), sp.Matrix([0, 1])
        for l in range(j + 1):
            o = links[l][2]
            cols[angle(l)] = sp.Matrix([-(p[1] - o[1]), p[0] - o[0]])
        return sp.Matrix.hstack(*cols)

    def jw(j):
        return sp.Matrix([[1 if any(angle(l) == c for l in range(j + 1)) else 0 for c in range(d)]])

    M = sp.zeros(d, d)
    for j, (mass, J, _, centre) in enumerate(links):
        A = jv(j, centre)
        W = jw(j)
        M += mass * A.T * A + J * W.T * W
    Jc = sp.Matrix.vstack(*[sp.Matrix(n).T * jv(j, p) for (j, p, n, _) in contacts])
    qd = sp.Matrix(rates)
    G = Jc * M.inv() * Jc.T
    v0 = Jc * qd
    kk = [c[3] for c in contacts]
    N = len(contacts)

    def lcp(Mx, q):
        """w = Mx z + q >= 0, z >= 0, z.w = 0, by enumerating supports."""
        for mask in cartesian((0, 1), repeat=N):
            s = [i for i in range(N) if mask[i]]
            z = sp.zeros(N, 1)
            if s:
                sub = Mx.extract(s, s)
                if sub.det() == 0:
                    continue
                zs = sub.solve(-q.extract(s, [0]))
                for a, i in enumerate(s):
                    z[i] = zs[a]
            w = Mx * z + q
            if all(x >= 0 for x in z) and all(x >= 0 for x in w):
                return z
        raise RuntimeError("no solution")

    scale = sp.diag(*[1 + x for x in kk])
    if not unilateral and model == "newton":
        P = G.solve(scale * v0)
    elif not unilateral:
        P = scale * G.solve(v0)
    elif model == "newton":
        P = lcp(G, -(v0 + sp.Matrix([x * max(y, 0) for x, y in zip(kk, v0)])))
    else:
        pc = lcp(G, -v0)
        start = scale * pc
        P = start + lcp(G, G * start - v0)
    after = qd - M.inv() * Jc.T * P
    return M, Jc, G, v0, P, after


print("\n3a. Double pendulum striking a wall (examples/double-pendulum-wall.toml)")
pend = [(1, R(1, 3), (0, 0), (R(3, 5), R(-4, 5))), (1, R(1, 3), (R(6, 5), R(-8, 5)), (2, R(-11, 5)))]
wall = [(1, (R(14, 5), R(-14, 5)), (1, 0), R(1, 2))]
M, Jc, G, v0, P, after = chain_impact(pend, False, [1, 1], wall, False, "newton")
print(f"  q = (theta1, theta2 relative); M = {M.tolist()}, J_c = {Jc.tolist()}")
print(f"  g = {G[0]}, v0 = {v0[0]}, lambda = {P[0]}, q' after = {list(after)}"
      f" (absolute rates {after[0]}, {after[0] + after[1]})")

print("\n3b. Three-link leg landing on heel and toe (examples/leg-heel-toe.toml)")
leg = [
    (7, R(7, 48), (0, R(9, 10)), (R(3, 20), R(7, 10))),
    (3, R(1, 16), (R(3, 10), R(1, 2)), (R(3, 20), R(3, 10))),
    (1, R(1, 120), (0, R(1, 10)), (R(1, 20), R(1, 20))),
]
rates = [1, -1, R(1, 2), R(-3, 2), R(3, 2)]
feet = [(2, (R(-1, 10), 0), (0, -1), R(1, 5)), (2, (R(1, 5), 0), (0, -1), R(0))]
for unilateral in (False, True):
    for model in ("newton", "poisson"):
        M, Jc, G, v0, P, after = chain_impact(leg, True, rates, feet, unilateral, model)
        if not unilateral and model == "newton":
            print(f"  M(q) = {M.tolist()}")
            print(f"  J_c = {Jc.tolist()}")
            print(f"  G = {G.tolist()}, det G = {G.det()}, v0 = {list(v0)}")
        law = "unilateral" if unilateral else "simultaneous"
        print(f"  {law} {model}: P = {list(P)}")
        print(f"     normal velocities after = {list(Jc * after)}")
        print(f"     q' after = {list(after)}")
