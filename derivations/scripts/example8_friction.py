"""Example 8 (sphere in a corner) with Coulomb friction and a spin: an independent derivation
of the impulse-space model of src/impact/friction, in exact fractions (no SymPy, no crate).

Run: python3 derivations/scripts/example8_friction.py
(prose: derivations/friction-example-8.md)

The scene (world axes = body axes, centre C at the origin, everything in the xy-plane):
sphere m = 2, R = 1/2, J = 2mR^2/5 = 1/5; v_C0 = (3, 6, 0), omega0 = (0, 0, 4);
A1 = (R, 0, 0), outward normal n1 = (1, 0, 0), k1 = 1/2; A2 = (0, R, 0), n2 = (0, 1, 0),
k2 = 3/10; mu = 1/5 at both. The tangents are t_i = e_z x n_i: t1 = (0, 1), t2 = (-1, 0).

The impulse the obstacle applies to the body at A_i is F_i = -(p_i n_i + tau_i t_i) (p_i the
normal impulse; tau_i > 0 opposes a slip along +t_i). Then
    dv_C = F / m,   d omega = (r x F)_z / J,   v_A = v_C + omega e_z x r.
Part 1 derives the 4x4 inertance matrix G of (v1n, v1t, v2n, v2t) in (p1, tau1, p2, tau2)
by hand (and checks it against the kinematics above); part 2 integrates the model event by
event; part 3 prints every quantity, in the names of derivations/README.md.
"""

from fractions import Fraction as Fr
from itertools import product

# ---- the scene -----------------------------------------------------------------------------
m, R = Fr(2), Fr(1, 2)
J = 2 * m * R**2 / 5
vC0 = (Fr(3), Fr(6))
w0 = Fr(4)
r = [(R, Fr(0)), (Fr(0), R)]
n = [(Fr(1), Fr(0)), (Fr(0), Fr(1))]
t = [(-nn[1], nn[0]) for nn in n]  # e_z x n
k = [Fr(1, 2), Fr(3, 10)]
mu = [Fr(1, 5), Fr(1, 5)]
NC = 2
assert J == Fr(1, 5)


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1]


def cross_z(a, b):
    return a[0] * b[1] - a[1] * b[0]


def body_velocity(lam):
    """(v_C, omega) after the generalized impulse lam = (p1, tau1, p2, tau2)."""
    vx, vy, w = vC0[0], vC0[1], w0
    for i in range(NC):
        p, tau = lam[2 * i], lam[2 * i + 1]
        F = (-(p * n[i][0] + tau * t[i][0]), -(p * n[i][1] + tau * t[i][1]))
        vx += F[0] / m
        vy += F[1] / m
        w += cross_z(r[i], F) / J
    return (vx, vy), w


def contact_velocities(lam):
    """(v1n, v1t, v2n, v2t) from the kinematics v_A = v_C + omega e_z x r."""
    vC, w = body_velocity(lam)
    out = []
    for i in range(NC):
        vA = (vC[0] - w * r[i][1], vC[1] + w * r[i][0])
        out += [dot(n[i], vA), dot(t[i], vA)]
    return out


# ---- Part 1: the inertance matrix by hand --------------------------------------------------
# r_i is along n_i (a sphere), so r_i x n_i = 0 and r_i x t_i = R e_z: the normal impulse has
# no moment, a tangential impulse tau_j turns the sphere by d omega = -R tau_j / J, which moves
# contact i along t_i by -R^2 tau_j / J. Hence, with v = v0 - G lam,
#   g(in, jn) = n_i.n_j / m,  g(in, jt) = n_i.t_j / m,  g(it, jn) = t_i.n_j / m,
#   g(it, jt) = t_i.t_j / m + R^2 / J.
# n1.n2 = 0, n1.t2 = -1, t1.n2 = 1, t1.t2 = 0, 1/m = 1/2, R^2/J = 5/4:
h, q = 1 / m, R**2 / J
G = [
    # p1     tau1    p2    tau2
    [h, 0, 0, -h],  # v1n
    [0, h + q, h, q],  # v1t
    [0, h, h, 0],  # v2n
    [-h, q, 0, h + q],  # v2t
]
G = [[Fr(x) for x in row] for row in G]
v0 = contact_velocities([Fr(0)] * 4)
for j in range(4):  # check each column against the kinematics
    e = [Fr(0)] * 4
    e[j] = Fr(1)
    col = [a - b for a, b in zip(v0, contact_velocities(e))]
    assert col == [G[i][j] for i in range(4)], (j, col)
assert all(G[i][j] == G[j][i] for i in range(4) for j in range(4))
print("G (rows v1n v1t v2n v2t, columns p1 tau1 p2 tau2):")
for row in G:
    print("   ", [str(x) for x in row])
print("before impact: v1n0, v1t0, v2n0, v2t0 =", [str(x) for x in v0])
# v1 = (3, 8): A1 approaches at 3 and slips along +t1 (= +y) at 8;
# v2 = (6, -1): A2 approaches at 6 and slips along -t2 (= +x) at 1.


def solve(A, b):
    """Exact Gaussian elimination. None when the system has no solution; an AssertionError
    when it has many (not met here)."""
    N = len(b)
    M = [list(A[i]) + [b[i]] for i in range(N)]
    row, pivots = 0, []
    for c in range(N):
        piv = next((i for i in range(row, N) if M[i][c] != 0), None)
        if piv is None:
            continue
        M[row], M[piv] = M[piv], M[row]
        for i in range(N):
            if i != row and M[i][c] != 0:
                f = M[i][c] / M[row][c]
                M[i] = [a - f * bb for a, bb in zip(M[i], M[row])]
        pivots.append(c)
        row += 1
    if any(M[i][N] != 0 for i in range(row, N)):
        return None  # inconsistent
    assert row == N, "a family of solutions"
    return [M[i][N] / M[i][i] for i in range(N)]


def matvec(A, x):
    return [sum(a * b for a, b in zip(row, x)) for row in A]


def sign(x):
    return (x > 0) - (x < 0)


# ---- Part 2: the integration ---------------------------------------------------------------
# Compression s in [0, 1]: dv_in/ds = -v_in0 at both contacts.
# Newton on [1, 2]: dv_in/ds = -k_i v_in0.  Poisson on [1, 2]: dp_i/ds = k_i p_i^c.
# Tangential law of contact i in mode  'stick': dv_it/ds = 0;  +1 / -1 (slide along +-t_i):
# dtau_i = mu_i u dp_i.  A contact with slip v_it != 0 slides with u = sign(v_it); at zero slip
# every mode is tried: stick is consistent iff |tau_i'| <= mu_i p_i', slide u iff the slip
# it produces has the sense u (u v_it' > 0).


def rates(modes, phase, law, pc):
    """dLambda/ds = (p1', tau1', p2', tau2') under the given modes."""
    A, b = [], []
    for i in range(NC):
        row = [Fr(0)] * 4
        if phase == "compression" or law == "newton":
            # -G_n . lam' = -c v_in0  (c = 1 in compression, k_i under Newton)
            c = Fr(1) if phase == "compression" else k[i]
            A.append(G[2 * i])
            b.append(c * v0[2 * i])
        else:  # poisson
            row[2 * i] = Fr(1)
            A.append(row)
            b.append(k[i] * pc[i])
        row = [Fr(0)] * 4
        if modes[i] == "stick":
            A.append(G[2 * i + 1])
            b.append(Fr(0))
        else:
            row[2 * i + 1] = Fr(1)
            row[2 * i] = -mu[i] * modes[i]
            A.append(row)
            b.append(Fr(0))
    return solve(A, b)


def name(mo):
    return {"stick": "stick", 1: "slide+", -1: "slide-"}[mo]


def choose_modes(lam, phase, law, pc):
    v = [a - b for a, b in zip(v0, matvec(G, lam))]
    options = []
    for i in range(NC):
        vt = v[2 * i + 1]
        options.append([sign(vt)] if vt != 0 else ["stick", 1, -1])
    consistent = []
    for modes in product(*options):
        d = rates(modes, phase, law, pc)
        if d is None:
            # G has rank 3 (a disc in the plane has 3 velocities, the contacts 4): the
            # identity v1t - v2t = v1n + v2n makes some assignments contradictory.
            print(f"      try {[name(x) for x in modes]}: no solution (contradictory)")
            continue
        dv = [-x for x in matvec(G, d)]
        ok = all(d[2 * i] >= 0 for i in range(NC))
        for i in range(NC):
            if v[2 * i + 1] != 0:
                continue
            if modes[i] == "stick":
                ok &= abs(d[2 * i + 1]) <= mu[i] * d[2 * i]
            else:
                ok &= modes[i] * dv[2 * i + 1] > 0
        verdict = "consistent" if ok else "inconsistent"
        if len(list(product(*options))) > 1:
            print(f"      try {[name(x) for x in modes]}: rates {[str(x) for x in d]}, "
                  f"slip rates {[str(dv[1]), str(dv[3])]}: {verdict}")
        if ok:
            consistent.append((modes, d))
    assert consistent, "no consistent assignment"
    consistent.sort(key=lambda md: -sum(x == "stick" for x in md[0]))  # stick preferred
    if len(consistent) > 1:
        print("      NOTE: several consistent assignments:", [[name(x) for x in c[0]] for c in consistent])
    return consistent[0]


def integrate(law):
    print(f"\n==== {law} ====")
    s, lam = Fr(0), [Fr(0)] * 4
    pc = None
    events, Ef, Wn = [], Fr(0), [Fr(0)] * NC
    history = {i: [] for i in range(NC)}
    while s < 2:
        phase = "compression" if s < 1 else "restitution"
        end = Fr(1) if s < 1 else Fr(2)
        print(f"  at s = {s} ({phase}), Lambda = {[str(x) for x in lam]}")
        modes, d = choose_modes(lam, phase, law, pc)
        v = [a - b for a, b in zip(v0, matvec(G, lam))]
        dv = [-x for x in matvec(G, d)]
        nxt = end
        for i in range(NC):
            if modes[i] != "stick" and dv[2 * i + 1] * modes[i] < 0:
                nxt = min(nxt, s - v[2 * i + 1] / dv[2 * i + 1])
        ds = nxt - s
        print(f"    modes {[name(x) for x in modes]} on [{s}, {nxt}]: rates {[str(x) for x in d]}")
        for i in range(NC):
            if not history[i] or history[i][-1] != name(modes[i]):
                history[i].append(name(modes[i]))
            # work integrals: v linear in s over the segment
            vn_mid = v[2 * i] + dv[2 * i] * ds / 2
            vt_mid = v[2 * i + 1] + dv[2 * i + 1] * ds / 2
            Wn[i] += vn_mid * d[2 * i] * ds
            Ef += vt_mid * d[2 * i + 1] * ds  # = mu |v_t| dp when sliding, 0 when sticking
        lam = [a + b * ds for a, b in zip(lam, d)]
        s = nxt
        events.append(s)
        if s == 1:
            pc = [lam[0], lam[2]]
    return lam, pc, events, Ef, Wn, history, modes


def fmt(v):
    return "[" + ", ".join(str(x) for x in v) + "]"


# ---- Part 3: every quantity ----------------------------------------------------------------
T0 = m * dot(vC0, vC0) / 2 + J * w0**2 / 2
results = {}
for law in ("newton", "poisson"):
    lam, pc, events, Ef, Wn, history, modes = integrate(law)
    p1, tau1, p2, tau2 = lam
    vC, w = body_velocity(lam)
    v = contact_velocities(lam)
    T = m * dot(vC, vC) / 2 + J * w**2 / 2
    dEc = T0 - T
    Ep = sum(lam[i] * x for i, x in enumerate(matvec(G, lam))) / 2
    assert dEc == sum(Wn) + Ef  # energy balance: normal work + friction dissipation
    # tangential impulse on the body, -tau_i t_i, and contact velocity vector v_n n + v_t t
    Pt = [(-lam[2 * i + 1] * t[i][0], -lam[2 * i + 1] * t[i][1], Fr(0)) for i in range(NC)]
    vv = [(v[2 * i] * n[i][0] + v[2 * i + 1] * t[i][0], v[2 * i] * n[i][1] + v[2 * i + 1] * t[i][1], Fr(0)) for i in range(NC)]
    print(f"  --- {law}: results")
    print(f"  {law}.P1 = {p1}")
    print(f"  {law}.P2 = {p2}")
    print(f"  {law}.P1c = {pc[0]}")
    print(f"  {law}.P2c = {pc[1]}")
    print(f"  {law}.Pt1 = {fmt(Pt[0])}")
    print(f"  {law}.Pt2 = {fmt(Pt[1])}")
    print(f"  {law}.twist = {fmt([0, 0, w, vC[0], vC[1], 0])}")
    print(f"  {law}.v1 = {fmt(vv[0])}")
    print(f"  {law}.v2 = {fmt(vv[1])}")
    print(f"  {law}.v1x = {v[0]}")
    print(f"  {law}.v2x = {v[2]}")
    print(f"  {law}.Ep = {Ep}")
    print(f"  {law}.dEc = {dEc}")
    print(f"  {law}.Ef = {Ef}")
    print(f"  {law}.events = {fmt(events[:-1])}     (end s = {events[-1]})")
    for i in range(NC):
        print(f"  {law}.stick{i + 1} = {int(modes[i] == 'stick')}    modes: {' -> '.join(history[i])}")
    print(f"  (normal works {fmt(Wn)}; T0 = {T0}, T = {T}; slips after: v1t = {v[1]}, v2t = {v[3]})")


# ---- Part 4: the energetic law (Stronge), with its square roots carried exactly ------------
# On s >= 1 each active contact has dp_i/ds = p_i^c until its restitution work -int v_in dp_i
# reaches k_i^2 times its compression work int v_in dp_i; it is then free (p', tau' = 0).
# Both normal velocities are 0 at s = 1 and linear in s over a segment, so the first stop is
# at s = 1 + sqrt(X), X rational; after it the other contact's v_n is linear again with a new
# slope b, and its stop y past the first solves b y^2/2 + a sqrt(X) y + a X/2 = k^2 W_c / p^c:
# the discriminant a^2 X - b(a X - 2 k^2 W_c/p^c) is rational again (X is), so every value is
# in Q(sqrt X, sqrt D): no nested radical.
import math


class Q2:
    """a + b sqrt(X) + c sqrt(D) + d sqrt(X D), exact."""

    X = D = None

    def __init__(self, a=0, b=0, c=0, d=0):
        self.v = [Fr(a), Fr(b), Fr(c), Fr(d)]

    def __add__(self, o):
        o = o if isinstance(o, Q2) else Q2(o)
        return Q2(*[x + y for x, y in zip(self.v, o.v)])

    __radd__ = __add__

    def __neg__(self):
        return Q2(*[-x for x in self.v])

    def __sub__(self, o):
        return self + (-(o if isinstance(o, Q2) else Q2(o)))

    def __mul__(self, o):
        if not isinstance(o, Q2):
            return Q2(*[x * Fr(o) for x in self.v])
        a, b, c, d = self.v
        e, f, g, h = o.v
        X, D = Q2.X, Q2.D
        return Q2(a * e + b * f * X + c * g * D + d * h * X * D,
                  a * f + b * e + (c * h + d * g) * D,
                  a * g + c * e + (b * h + d * f) * X,
                  a * h + d * e + b * g + c * f)

    __rmul__ = __mul__

    def __float__(self):
        a, b, c, d = self.v
        return float(a) + float(b) * math.sqrt(Q2.X) + float(c) * math.sqrt(Q2.D) + float(d) * math.sqrt(Q2.X * Q2.D)

    def __str__(self):
        a, b, c, d = self.v
        parts = [f"{a}"] + [f"({x})*{r}" for x, r in ((b, f"sqrt({Q2.X})"), (c, f"sqrt({Q2.D})"), (d, f"sqrt({Q2.X * Q2.D})")) if x]
        return " + ".join(parts) + f"  (~ {float(self):.9f})"


def energetic():
    print("\n==== energetic ====")
    lam, pc, events, Ef, Wn, history, modes = None, None, None, None, None, None, None
    # compression as before (the law does not enter it)
    s, lam = Fr(0), [Fr(0)] * 4
    Wc = [Fr(0)] * NC
    while s < 1:
        mo, d = choose_modes(lam, "compression", None, None)
        v = [a - b for a, b in zip(v0, matvec(G, lam))]
        dv = [-x for x in matvec(G, d)]
        nxt = Fr(1)
        for i in range(NC):
            if mo[i] != "stick" and dv[2 * i + 1] * mo[i] < 0:
                nxt = min(nxt, s - v[2 * i + 1] / dv[2 * i + 1])
        ds = nxt - s
        for i in range(NC):
            Wc[i] += (v[2 * i] + dv[2 * i] * ds / 2) * d[2 * i] * ds
        lam = [a + b * ds for a, b in zip(lam, d)]
        s = nxt
    pc = [lam[0], lam[2]]
    print(f"  compression works W_c = {fmt(Wc)}, p^c = {fmt(pc)}")
    # s = 1: the mode of each contact, with p' = p^c (Poisson's rates with k = 1)
    print("  at s = 1, modes with p' = p^c:")
    mo, d = choose_modes(lam, "restitution", "poisson", [pc[0] * 2, pc[1] * 10 / 3])
    assert [d[0], d[2]] == pc
    dv = [-x for x in matvec(G, d)]
    a = [-dv[0], -dv[2]]  # v_in = -a_i (s - 1)
    Xs = [2 * k[i] ** 2 * Wc[i] / (a[i] * pc[i]) for i in range(NC)]  # (s - 1)^2 at each stop
    j = min(range(NC), key=lambda i: Xs[i])  # the first to stop
    i = 1 - j
    Q2.X = Xs[j]
    print(f"    modes {[name(x) for x in mo]}, rates {fmt(d)}, v_n slopes {fmt([-x for x in a])}")
    print(f"    contact {j + 1} stops first, at s = 1 + sqrt({Xs[j]})  (~ {1 + math.sqrt(Xs[j]):.9f})")
    # slips keep their senses on [1, s_a]: they start at 0 and grow with the chosen senses
    # second segment: contact j free, contact i slides on in its sense u
    u = mo[i]
    assert u in (1, -1)
    d2 = [Fr(0)] * 4
    d2[2 * i] = pc[i]
    d2[2 * i + 1] = mu[i] * u * pc[i]
    dv2 = [-x for x in matvec(G, d2)]
    b = -dv2[2 * i]
    C = k[i] ** 2 * Wc[i] / pc[i]
    Q2.D = a[i] ** 2 * Xs[j] - b * (a[i] * Xs[j] - 2 * C)
    xa = Q2(0, 1)
    y = (Q2(0, -a[i]) + Q2(0, 0, 1)) * (1 / b)  # (-a sqrt X + sqrt D) / b
    end = Q2(1) + xa + y
    print(f"    then contact {i + 1} alone (slide{'+' if u > 0 else '-'}), v_n slope {-b}; it stops at s = {end}")
    # its slip must not vanish on the way: v_it at s_a and at the end
    L = [Q2(x) for x in lam]
    La = [x + xa * dd for x, dd in zip(L, d)]
    Lend = [x + y * dd for x, dd in zip(La, d2)]
    vt = lambda LL, c: Q2(v0[2 * c + 1]) - sum((LL[q] * G[2 * c + 1][q] for q in range(4)), Q2())
    print(f"    slips at the first stop: {float(vt(La, 0)):.6f}, {float(vt(La, 1)):.6f}; "
          f"contact {i + 1} at the end: {float(vt(Lend, i)):.6f}")
    assert u * float(vt(La, i)) > 0 and u * float(vt(Lend, i)) > 0
    assert mo[j] * float(vt(La, j)) > 0
    p1, tau1, p2, tau2 = Lend
    vx = Q2(vC0[0]) - (p1 * n[0][0] + tau1 * t[0][0] + p2 * n[1][0] + tau2 * t[1][0]) * (1 / m)
    vy = Q2(vC0[1]) - (p1 * n[0][1] + tau1 * t[0][1] + p2 * n[1][1] + tau2 * t[1][1]) * (1 / m)
    w = Q2(w0) - (tau1 + tau2) * (R / J)
    T = (vx * vx + vy * vy) * (m / 2) + w * w * (J / 2)
    print(f"  energetic.P1 = {p1}")
    print(f"  energetic.P2 = {p2}")
    print(f"  energetic.P1c = {pc[0]}, energetic.P2c = {pc[1]}")
    print(f"  energetic.Pt1 = [0, {-tau1}, 0]")
    print(f"  energetic.Pt2 = [{tau2}, 0, 0]")
    print(f"  energetic.twist = [0, 0, {w}, {vx}, {vy}, 0]")
    print(f"  energetic.dEc = {Q2(T0) - T}")
    print(f"  energetic.events = [8/39, 1, {Q2(1) + xa}]")
    print(f"  energetic.end = {end}")
    print(f"  modes: contact {i + 1} ends sliding, contact {j + 1} free: stick1 = stick2 = 0")


energetic()
