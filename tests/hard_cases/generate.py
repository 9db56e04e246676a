#!/usr/bin/env python3
"""Regenerate the hard-case corpus (tests/hard_cases/*.toml) for tests/hard_cases.rs.

Every number is written as a short decimal, so each scene is exactly rational: the exact
solve is the reference, and f64/f32 see the same inputs rounded once. Run from this folder."""
import random

random.seed(20261121)

def scene(name, category, body, contacts, constraints="", models=("newton", "poisson")):
    m, j, v, w = body
    out = [f'# {category}', f'name = "{name}"', '[body]', f'mass = {m}',
           f'inertia = [{", ".join(j)}]', f'velocity = [{", ".join(v)}]',
           f'angular_velocity = [{", ".join(w)}]']
    for p, n, k in contacts:
        out += ['[[contact]]', f'point = [{", ".join(p)}]', f'normal = [{", ".join(n)}]']
        out += [f'k = {k}'] if isinstance(k, str) else [f'k_newton = {k[0]}', f'k_poisson = {k[1]}']
    out += [constraints] if constraints else []
    out += ['[solve]', 'models = [' + ', '.join(f'"{x}"' for x in models) + ']']
    with open(f'{name}.toml', 'w') as f:
        f.write('\n'.join(out) + '\n')

unit = ('1', ['0.4', '0.4', '0.4'], ['1', '0', '0'], ['0', '0', '0.5'])
X = ['1', '0', '0']
# Nearly coincident contact points: separations 1e-6 … 1e-12 of the body's size (1).
for e in (6, 8, 10, 12):
    scene(f'near-coincident-1e-{e}', f'nearly coincident points, separation 1e-{e}', unit,
          [(['0', '0.5', '0'], X, ('0.3', '0.3')), (['0', f'0.5{"0" * (e - 2)}1', '0'], X, ('0.6', '0.2'))])
# Mass-to-inertia ratios up to 1e8, both ways.
scene('mass-ratio-1e8', 'mass / inertia = 1e8', ('1e8', ['1', '1', '1'], ['1', '0', '0'], ['0', '0', '1e-4']),
      [(['0', '-1', '0'], X, '0.5'), (['0', '2', '0'], X, '0.2')])
scene('mass-ratio-1e-8', 'mass / inertia = 1e-8', ('1e-4', ['1e4', '1e4', '1e4'], ['1', '0', '0'], ['0', '0', '1e-4']),
      [(['0', '-1', '0'], X, '0.5'), (['0', '2', '0'], ['1', '0.5', '0'], '0.2')])
# Contact points 1e4 away from C.
scene('far-points-1e4', 'contact points 1e4 from C', ('3', ['2', '5', '7'], ['1', '2', '-1'], ['0.1', '0', '0.3']),
      [(['1e4', '0', '0'], ['0', '1', '0'], '0.5'), (['0', '1e4', '0'], ['1', '0', '0.5'], '0.3'), (['0', '0', '-1e4'], ['1', '1', '1'], '0.7')])
# Nearly parallel contact wrenches: one point, normals 1e-7 apart.
scene('nearly-parallel-1e-7', 'nearly parallel wrenches at one point', ('2', ['1', '2', '3'], ['1', '0.5', '0'], ['0', '0', '0.2']),
      [(['0', '1', '0'], X, ('0.4', '0.4')), (['0', '1', '0'], ['1', '0.0000001', '0'], ('0.8', '0.1'))])
# k at 0 and at 1.
for k in ('0', '1'):
    scene(f'restitution-{k}', f'every k = {k}', ('2', ['1', '2', '3'], ['1', '0.5', '-0.25'], ['0.5', '0', '0.2']),
          [(['0.5', '-1', '0.25'], ['1', '0', '0.5'], k), (['-0.5', '1', '0'], ['1', '0.25', '0'], k), (['0', '0', '1'], ['0.5', '0', '1'], k)])
# 2 to 12 contacts, random directions around a body (well conditioned up to N = 6; more
# contacts than the 6 directions of a free body are exactly singular).
for n in (2, 3, 4, 6, 8, 12):
    cs = []
    for i in range(n):
        p = [f'{random.randint(-20, 20) / 10}' for _ in range(3)]
        d = [f'{random.randint(-10, 10) / 10}' for _ in range(3)]
        if all(float(x) == 0 for x in d):
            d[0] = '1'
        cs.append((p, d, (f'{random.randint(0, 10) / 10}', f'{random.randint(0, 10) / 10}')))
    scene(f'contacts-{n}', f'{n} contacts' + (' (N > 6: singular)' if n > 6 else ''),
          ('5', ['1.5', '2', '2.5'], ['1', '-0.5', '0.25'], ['0.3', '0.2', '-0.1']), cs)
# Exactly singular: coincident points, one line of action.
scene('coincident-equal-k', 'coincident points, same normal, equal k (compatible)', unit,
      [(['0', '0.5', '0'], X, '0.5'), (['0', '0.5', '0'], X, '0.5')])
scene('coincident-unequal-k', 'coincident points, same normal, unequal k (incompatible)', unit,
      [(['0', '0.5', '0'], X, '0.5'), (['0', '0.5', '0'], X, '0.25')])
scene('same-line', 'two points on one line of action (identical screws)', unit,
      [(['1', '0.5', '0'], X, '0.3'), (['3', '0.5', '0'], X, '0.3')])
# Constrained: Example 5 (one degree of freedom) is exactly singular; nearly singular with
# two degrees of freedom and nearly coincident contacts.
bar = ('3', ['4', '1', '4'], ['-2', '0', '0'], ['0', '0', '1'])
joint = '[[constraints.joint]]\nkind = "revolute"\npoint = [0, -2, 0]\naxis = [0, 0, 1]'
for name, k2 in (('constrained-singular-compatible', '0.2'), ('constrained-singular-incompatible', '0.7')):
    scene(name, 'one degree of freedom, two contacts (Example 5)', bar,
          [(['0', '-0.5', '0'], X, '0.2'), (['0', '1', '0'], X, k2)], joint)
slide = '[[constraints.joint]]\nkind = "revolute"\npoint = [0, -1, 0]\naxis = [0, 0, 1]\n[[constraints.joint]]\nkind = "prismatic"\naxis = [1, 0, 0]'
for e in (4, 7):
    scene(f'constrained-near-singular-1e-{e}', f'two degrees of freedom, contacts 1e-{e} apart (Example 6)',
          ('10', ['3.3', '3.3', '3.3'], ['0', '0', '0'], ['0', '0', '1']),
          [(['0', '-0.3', '0'], X, '0.5'), (['0', f'-0.3{"0" * (e - 2)}1', '0'], X, '0.3')], slide)
