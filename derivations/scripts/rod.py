"""The slender rod striking a rough floor at one end: closed forms of the impulse-space model
of src/impact/friction (see derivations/friction-rod.md for the prose).

Run: python3 derivations/scripts/rod.py   (needs sympy)

Part 1 derives the inertance block of the rod's end from the rigid-body kinematics, the
thresholds of the mode tests in src/impact/friction/modes.rs, and the closed forms of every
regime, symbolically. Part 2 evaluates them at the rational points that
tests/friction_closed_forms.rs and derivations/friction-rod.md use.

Conventions (world axes): the floor is y = 0, its upward normal e_y; the rod's centre C is
at the origin, its lower end A at C - L (c, s) with c = cos(theta), s = sin(theta). The
contact's outward normal (out of the body, into the floor) is n = -e_y; its tangent
t = e_z x n = +e_x. Before impact v_C = (U, -V) with V > 0 (approach), omega = 0, so
v_n0 = n . v_A = V and the slip v_t0 = t . v_A = U. The floor applies (-tau, p) at A.
"""

import sympy as sp

m, L, c, s, mu, k, V, U = sp.symbols("m L c s mu k V U", real=True)
J = m * L**2 / 3


def reduce(e):
    """Simplify modulo s^2 + c^2 = 1 (c^2 written as 1 - s^2 where it shortens)."""
    e = sp.factor(sp.together(e))
    n, d = sp.fraction(e)
    n = sp.reduced(sp.expand(n), [c**2 + s**2 - 1], c, s)[1]
    d = sp.reduced(sp.expand(d), [c**2 + s**2 - 1], c, s)[1]
    return sp.factor(n / d)


def zero(e):
    """e == 0 modulo s^2 + c^2 = 1 (the numerator reduces to 0)."""
    n = sp.numer(sp.together(e))
    return sp.reduced(sp.expand(n), [c**2 + s**2 - 1], c, s)[1] == 0


# ---- Part 1: the inertance block from the kinematics --------------------------------------
p, tau = sp.symbols("p tau")
r = sp.Matrix([-L * c, -L * s])  # A - C
F = sp.Matrix([-tau, p])  # impulse on the body at A
dvC = F / m
dw = (r[0] * F[1] - r[1] * F[0]) / J
dvA = dvC + dw * sp.Matrix([-r[1], r[0]])  # omega x r in the plane
dvn, dvt = -dvA[1], dvA[0]  # n = -e_y, t = +e_x
G = -sp.Matrix([[sp.diff(dvn, p), sp.diff(dvn, tau)], [sp.diff(dvt, p), sp.diff(dvt, tau)]])
G = G.applyfunc(sp.simplify)
gnn, gnt, gtt = G[0, 0], G[0, 1], G[1, 1]
det = reduce(G.det())
print("g_nn =", gnn, "  g_nt =", gnt, "  g_tt =", gtt, "  g_tn =", G[1, 0])
print("det G =", det)
assert sp.simplify(G[0, 1] - G[1, 0]) == 0
assert zero(det - 4 / m**2)

# Sliding in sense u (dtau = mu u dp): dv_n/dp = -a_u, dv_t/dp = -b_u.
a = {u: gnn + u * mu * gnt for u in (1, -1)}
b = {u: gnt + u * mu * gtt for u in (1, -1)}
# Sticking (v_t held at 0): dtau/dp = -g_nt/g_tt, dv_n/dp = -g*.
gstar = reduce(gnn - gnt**2 / gtt)
print("g* = det/g_tt =", gstar)

# Mode tests of modes.rs at zero slip (p' > 0):
#   stick:   |tau'| <= mu p'  with tau' = -(g_nt/g_tt) p'   <=>  mu >= |g_nt|/g_tt
#   slide+:  v_t' = -b_+ p' > 0  <=>  b_+ < 0               (never, g_nt > 0)
#   slide-:  v_t' = -b_- p' < 0  <=>  b_- > 0  <=>  mu < g_nt/g_tt
mubar = reduce(gnt / gtt)
print("mu_bar (stick iff mu >= mu_bar; reversal to slide- iff mu < mu_bar) =", mubar)
print("slide- keeps p' > 0 iff a_- > 0 iff mu <", reduce(gnn / gnt))
# A backward slip (U < 0) decelerates iff b_- < 0 iff mu > mu_bar.

# Threshold ratios of U/V (forward slip, U > 0): the slip stops
#   in compression  iff U/V <  b_+/a_+
#   in restitution  iff b_+/a_+ <= U/V < (1+k) b_+/a_+   (Newton and Poisson alike)
#   never (gross)   iff U/V >= (1+k) b_+/a_+
print("stop ratio b_+/a_+ =", reduce(b[1] / a[1]))
print("backward stop ratio b_-/a_- =", reduce(b[-1] / a[-1]))

# Impulses of a stick that lasts to the end of compression: G [p; tau] = [V; U].
pc_stick = reduce((V * gtt - U * gnt) / det)
print("p^c when the slip stops in compression and sticks: (V g_tt - U g_nt)/det =", pc_stick)
# Check: slide to p_stop = U/b_+, then stick with p' = V/g* to s = 1.
pstop = U / b[1]
s1 = a[1] * pstop / V
assert zero(pstop + (1 - s1) * V / gstar - pc_stick)

# Newton vs Poisson after a stop in compression followed by stick (v_t = 0 at the end):
P_newton = reduce(pc_stick + k * V / gstar)
P_poisson = reduce((1 + k) * pc_stick)
print("P (Newton, stop in compression, stick) =", P_newton)
print("P (Poisson, stop in compression, stick) =", P_poisson)


def energy_loss(P, tau_, vn0=V, vt0=U):
    """T0 - T for the impulse (P, tau_) at the contact: Lambda . (v0 + v)/2."""
    vn = vn0 - gnn * P - gnt * tau_
    vt = vt0 - gnt * P - gtt * tau_
    return (P * (vn0 + vn) + tau_ * (vt0 + vt)) / 2


# Newton with stick at the end: the final contact velocity is (-kV, 0), so
# Lambda = G^-1 (V(1+k), U) and dEc = [g_tt V^2 (1-k^2) - 2 g_nt U V + g_nn U^2] / (2 det).
tau_N = reduce((U - gnt * P_newton) / gtt)
dE_newton = reduce(energy_loss(P_newton, tau_N))
print("dEc (Newton, stop in compression, stick) =", dE_newton)
assert zero(dE_newton - (gtt * V**2 * (1 - k**2) - 2 * gnt * U * V + gnn * U**2) / (2 * det))

# ---- Part 2: the regimes evaluated exactly ---------------------------------------------------


def rod(law, cs, mass, half, V0, U0, mu0, k0):
    """Closed-form outcome at a rational point. Returns a dict of exact values."""
    cc, ss = cs
    sub = {c: cc, s: ss, m: mass, L: half, mu: mu0, k: k0, V: V0, U: U0}
    Gnn, Gnt, Gtt = (sp.nsimplify(x.subs(sub)) for x in (gnn, gnt, gtt))
    gs = Gnn - Gnt**2 / Gtt
    mb = Gnt / Gtt

    def A(mode):
        return gs if mode == "stick" else Gnn + mode * mu0 * Gnt

    def B(mode):
        return 0 if mode == "stick" else Gnt + mode * mu0 * Gtt

    def dtau(mode):
        return -mb if mode == "stick" else mode * mu0

    # Mode sequence and the impulse at which the slip stops.
    if U0 == 0:
        m0 = "stick" if mu0 >= mb else -1
        seq, pst = [m0], None
    else:
        u = 1 if U0 > 0 else -1
        bu = B(u)
        if u * bu > 0:
            seq, pst = [u, "stick" if mu0 >= mb else -1], U0 / bu
        else:
            seq, pst = [u], None
    for md in seq:
        assert A(md) > 0, "tensile rate: outside the tested regimes"
    # Compression: p' = V/a.
    if pst is not None and A(seq[0]) * pst / V0 < 1:
        s_stop = A(seq[0]) * pst / V0
        pc = pst + (1 - s_stop) * V0 / A(seq[1])
        v1 = V0 * (1 - s_stop)
        Wc = (V0 + v1) / 2 * pst + v1 / 2 * (pc - pst)
        rmode = seq[1]
        rstop = None
    else:
        s_stop = None
        pc = V0 / A(seq[0])
        Wc = V0 * pc / 2
        rmode = seq[0]
        rstop = pst if len(seq) == 2 else None
    # Restitution: p' = k p^c (Poisson, energetic) or k V / a (Newton); sigma = s - 1.
    events = [s_stop] if s_stop is not None else []
    if law == "poisson":
        P = (1 + k0) * pc
        if rstop is not None and rstop < P:
            events.append(1 + (rstop - pc) / (k0 * pc))
            seq_used = seq
        else:
            seq_used = seq if s_stop is not None else [seq[0]]
    elif law == "newton":
        pend = pc + k0 * V0 / A(rmode)
        if rstop is not None and rstop < pend:
            sig = (rstop - pc) * A(rmode) / (k0 * V0)
            events.append(1 + sig)
            P = rstop + (1 - sig) * k0 * V0 / A(seq[1])
            seq_used = seq
        else:
            P = pend
            seq_used = seq if s_stop is not None else [seq[0]]
    else:  # energetic: W_r(p) = int_{pc}^{p} a (q - pc) dq piecewise, stop at W_r = k^2 W_c
        target = k0**2 * Wc
        a0 = A(rmode)
        if rstop is not None:
            W1 = a0 * (rstop - pc) ** 2 / 2
        if rstop is None or W1 >= target:
            P = pc + sp.sqrt(2 * target / a0)
            seq_used = seq if s_stop is not None else [seq[0]]
        else:
            a1 = A(seq[1])
            x = (-a0 * (rstop - pc) + sp.sqrt((a0 * (rstop - pc)) ** 2 + 2 * a1 * (target - W1))) / a1
            P = rstop + x
            events.append(1 + (rstop - pc) / pc)
            seq_used = seq
        P = sp.radsimp(P)
    # Tangential impulse and friction work, mode by mode: on a slide, v_t is linear in p
    # and the work mu u int v_t dp is the trapezoid rule.
    if len(seq_used) == 2:
        pieces = [(seq[0], 0, pst, U0), (seq[1], pst, P, 0)]
    else:
        pieces = [(seq_used[0], 0, P, U0)]
    T, Ef = 0, 0
    for md, pa, pb, vt_a in pieces:
        T += (pb - pa) * dtau(md)
        if md != "stick":
            Ef += md * mu0 * (vt_a + vt_a - B(md) * (pb - pa)) / 2 * (pb - pa)
    vn = V0 - Gnn * P - Gnt * T
    vt = U0 - Gnt * P - Gtt * T
    dE = (P * (V0 + vn) + T * (U0 + vt)) / 2
    Ep = (Gnn * P**2 + 2 * Gnt * P * T + Gtt * T**2) / 2
    # Twist after: v_C = (U - tau/m, -V + P/m) (world), omega = -3 (c P + s tau) / (m L).
    w = -3 * (cc * P + ss * T) / (mass * half)
    vC = (U0 - T / mass, -V0 + P / mass)
    tidy = lambda x: sp.radsimp(sp.expand(x))  # noqa: E731
    return dict(
        modes=["stick" if md == "stick" else ("slide+" if md == 1 else "slide-") for md in seq_used],
        events=events, Pc=pc, P=tidy(P), tau=tidy(T), vn=tidy(vn), vt=tidy(vt),
        dEc=tidy(dE), Ep=tidy(Ep), Ef=tidy(Ef), Wc=Wc, omega=tidy(w), vC=tuple(tidy(x) for x in vC),
    )


R = sp.Rational


def report(name, law, cs, mass, half, V0, U0, mu0, k0):
    """The planned quantities of derivations/friction-rod.md, in body axes (x along the rod:
    world (X, Y) -> (X c + Y s, -X s + Y c))."""
    cc, ss = cs
    o = rod(law, cs, mass, half, V0, U0, mu0, k0)
    body = lambda X, Y: (sp.radsimp(X * cc + Y * ss), sp.radsimp(-X * ss + Y * cc))  # noqa: E731
    n, t = (-ss, -cc), (cc, -ss)
    pt = [sp.radsimp(-o["tau"] * x) for x in t] + [0]
    v1 = [sp.radsimp(o["vn"] * a + o["vt"] * b) for a, b in zip(n, t)] + [0]
    twist = [0, 0, o["omega"], *body(*o["vC"]), 0]
    stick = 1 if o["modes"][-1] == "stick" and mu0 != 0 else 0
    print(f"# {name}: {law}, modes {o['modes']}")
    for key, val in [("P1", o["P"]), ("P1c", o["Pc"]), ("Pt1", pt), ("twist", twist), ("v1", v1),
                     ("Ep", o["Ep"]), ("dEc", o["dEc"]), ("Ef", o["Ef"]), ("stick1", stick),
                     ("events", o["events"])]:
        print(f"{law}.{key} = {val}")


if __name__ == "__main__":
    print()
    # The Kane-type example: theta with (c, s) = (3/5, 4/5), m = L = 1, V = 1, U = 1/2,
    # mu = 1, k = 9/10: the slip stops in compression and the end sticks.
    print("Newton gains energy (stop in compression, then stick) for some U iff k^2 >",
          reduce(det / (gnn * gtt)))
    # Poisson in the same regime: P = (1+k) p^c, the end sticks.
    tau_P = reduce((U - gnt * P_poisson) / gtt)
    print("dEc (Poisson, stop in compression, stick) =", reduce(energy_loss(P_poisson, tau_P)))
    print()
    cs = (R(3, 5), R(4, 5))
    scenes = [
        ("stop-stick", cs, R(1, 4), R(1, 2), R(1, 2)),
        ("stop-reverse", cs, R(1, 4), R(1, 4), R(1, 2)),
        ("gross-slip", cs, 3, R(1, 4), R(1, 2)),
        ("kane", cs, R(1, 2), 1, R(9, 10)),
    ]
    for name, cs_, U0, mu0, k0 in scenes:
        for law in ("newton", "poisson", "energetic"):
            report(name, law, cs_, 1, 1, 1, U0, mu0, k0)
        print()
