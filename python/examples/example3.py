"""The paper's Example 3 from Python, notebook style: a planar bar striking two supports.

Run: python python/examples/example3.py   (from the repository root, after `pip install ./python`)
"""

# %% Load the scene (examples/planar-bar.toml) once; every call below reuses it.
import pathlib

import inertance

ROOT = pathlib.Path(__file__).resolve().parents[2]
bar = inertance.Scene.load(ROOT / "examples" / "planar-bar.toml")

# %% Solve exactly: impulses (eq. 20, 23) and energies (eq. 28, 32) as Fractions.
exact = inertance.solve(bar, exact=True)
print("Newton P  =", exact.newton.impulses)                    # [329/90, 89/450]
print("Newton Ep =", exact.newton.lost_velocity_energy)        # 413791/45000
print("Poisson P =", exact.poisson.impulses)                   # [91/25, 6/25]

# %% The same in f64: numpy arrays.
f = inertance.solve(bar)
print("f64 Newton P =", f.newton.impulses, " v_C after =", f.newton.velocity)

# %% Sweep k2 over [0, 1]: Newton against Poisson (they meet at k2 = k1 = 0.3, eq. 50-55).
cols = inertance.sweep(bar, {"contact[1].k": (0, 1, 101)}, frame=False)
k2 = cols["contact[1].k"]
gap = abs(cols["newton_P2"] - cols["poisson_P2"])
print(f"Newton and Poisson P2 closest at k2 = {k2[gap.argmin()]:.2f}")
try:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots()
    for name, style in (("newton", "-"), ("poisson", "--")):
        ax.plot(k2, cols[f"{name}_P1"], style, label=f"{name} P1")
        ax.plot(k2, cols[f"{name}_P2"], style, label=f"{name} P2")
        ax.plot(k2, cols[f"{name}_dEc"], style, label=f"{name} ΔE_c")
    ax.set_xlabel("k2")
    ax.legend()
    fig.savefig("example3-k2.png")
    print("plot written to example3-k2.png")
except ImportError:
    print("(matplotlib not installed: no plot)")

# %% A closed form into SymPy: the Poisson impulses for any bar (the symbolic scene).
symbolic = bar.toml
for old, new in (("mass = 1", 'mass = "m"'), ("[12, 1.6, 12]", '["Jx", "Jy", "Jz"]'),
                 ("[3, 2, 0]", '["vx", "vy", 0]'), ("[0, 0, 0.4]", '[0, 0, "omega"]'),
                 ("[0, -2, 0]", '[0, "y1", 0]'), ("[0, 4, 0]", '[0, "y2", 0]'),
                 ("k = 0.3", 'k = "k1"'), ("k = 0.2", 'k = "k2"')):
    symbolic = symbolic.replace(old, new)
d = inertance.derive(symbolic, symbols="m Jx Jy Jz vx vy omega y1 y2 k1 k2".split(), model="poisson")
P1 = d.model("poisson")["impulses"][0]
print("Poisson P1 =", P1)
try:
    import sympy

    values = dict(m=1, Jz=12, y1=-2, y2=4, vx=3, omega=sympy.Rational(2, 5), k1=sympy.Rational(3, 10))
    at = P1.subs({sympy.Symbol(k): v for k, v in values.items()})
    print("at Example 3:", at, "=", exact.poisson.impulses[0])
    assert at == sympy.Rational(exact.poisson.impulses[0].numerator, exact.poisson.impulses[0].denominator)
except ImportError:
    pass
