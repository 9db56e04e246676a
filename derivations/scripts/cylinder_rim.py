"""A cylinder's rim against a plane: its nearest point, gap, rate and the velocity of the nearest
point around the rim, as src/simulate/world.rs computes them (derivations/cylinder-rim-kinematics.md
for the prose).

Run: python3 derivations/scripts/cylinder_rim.py   (needs sympy)

World axes. The plane has unit normal N = e_z (any unit N, by a rotation). The rim: centre
x_c = C + r_c, unit axis a (both turning with the body at angular velocity w), radius rho.
"""

import sympy as sp

t = sp.symbols("t", real=True)
phi, rho = sp.symbols("phi rho", positive=True)
w = sp.Matrix(sp.symbols("w1 w2 w3", real=True))
N = sp.Matrix([0, 0, 1])
ax, ay, az = (sp.Function(n)(t) for n in ("a_x", "a_y", "a_z"))
a = sp.Matrix([ax, ay, az])
unit = {az: sp.sqrt(1 - ax**2 - ay**2)}

# 1. The nearest point. Two unit vectors e1, e2 complete a to an orthonormal frame; the rim is
#    x_c + rho (cos phi e1 + sin phi e2), its height above the plane N.x_c + rho (cos phi N.e1 +
#    sin phi N.e2), least at rho times -sqrt((N.e1)^2 + (N.e2)^2) = -sqrt(1 - s^2), s = N.a:
#    the point x_c - rho u with u = (N - s a)/sqrt(1 - s^2), the unit vector of the rim's plane
#    most along N.
s = (N.T * a)[0]
tilt = sp.sqrt(1 - s**2)
u = (N - s * a) / tilt
assert sp.simplify((u.T * u)[0].subs(unit) - 1) == 0, "u is a unit vector"
assert sp.simplify((u.T * a)[0].subs(unit)) == 0, "u lies in the rim's plane"
# the height along the rim, on a frame e1 = u, e2 = a x u: least at phi = 0 (the point -rho u)
e1, e2 = u, a.cross(u)
height = -rho * (sp.cos(phi) * (N.T * e1)[0] + sp.sin(phi) * (N.T * e2)[0])
assert sp.simplify((N.T * e2)[0].subs(unit)) == 0
assert sp.simplify(height.subs(unit) + rho * sp.cos(phi) * tilt.subs(unit)) == 0
print("nearest point x_c - rho u, gap N.(x_c - P) - rho sqrt(1 - s^2): checked")

# 2. Its velocity around the rim. With a' = w x a (a turns with the body):
#    s' = N.(w x a),
#    u' = (-s' a - s (w x a))/sqrt(1 - s^2) + (N - s a) s s'/(1 - s^2)^(3/2)
adot = w.cross(a)
rule = {sp.Derivative(ax, t): adot[0], sp.Derivative(ay, t): adot[1], sp.Derivative(az, t): adot[2]}
du_exact = u.diff(t).subs(rule)
ds = (N.T * adot)[0]
du_code = (-a * ds - adot * s) / tilt + (N - a * s) * (s * ds / tilt**3)
assert sp.simplify((du_exact - du_code).subs(unit)) == sp.zeros(3, 1), "u' as the code has it"
print("u' = (-s' a - s (w x a))/sqrt(1 - s^2) + (N - s a) s s'/(1 - s^2)^(3/2): checked")

# 3. The rate of the gap is the body point's at the nearest point (the envelope theorem): the
#    nearest point's own motion around the rim, -rho u', has no component along N.
assert sp.simplify((N.T * du_code)[0].subs(unit) - sp.diff(tilt, t).subs(rule).subs(unit)) == 0
#    d/dt of -rho sqrt(1 - s^2) is rho s s'/sqrt(1 - s^2); the body point's contribution
#    N.(w x (-rho u)) equals it, so N.(-rho u') adds nothing:
body = (N.T * w.cross(-rho * u))[0]
assert sp.simplify((body - sp.diff(-rho * tilt, t).subs(rule)).subs(unit)) == 0
print("gap rate = N . (v + w x r_p), the body point's at the nearest point: checked")

# 4. How fast the nearest point runs around the rim near flat: a = (sin th, 0, cos th), a tilt
#    th about e_y. A spin about N or a change of the tilt moves it at |u'| <= W; a turn about
#    the axis across (e_x: the face rocking sideways) moves it at W cos^2 th / sin th, without
#    bound as th -> 0 — why a rim within FLAT of flat is carried by its body points.
th, W = sp.symbols("theta W", positive=True)
at = {ax: sp.sin(th), ay: 0}
for wv, label in [((0, 0, W), "spin about N"), ((0, W, 0), "tilting"), ((W, 0, 0), "across")]:
    val = du_code.subs(dict(zip(w, wv))).subs(unit).subs(at)
    print(f"  w {label}: |u'| = {sp.simplify(sp.sqrt((val.T * val)[0]))}")
