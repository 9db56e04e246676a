//! One pass over a batch at L lanes: read L scenes into [`Lanes`], decide lane by lane
//! whether the input is valid and whether the lean route takes it, solve all L by the lean
//! arithmetic, write the lanes out.
//!
//! Everything the common case does is lane arithmetic or a lane-wise comparison, so it
//! vectorises at any L: the validity checks ([`valid`]), the route test ([`routed`], the
//! operations of [`crate::impact::lean::route_test`] in its order, on lanes) and the test that
//! the outputs are finite (Σ 0·x = 0). Only a chunk with a lane off the lean route goes lane by
//! lane: there the scalar route test decides each lane again (the same operations, hence the
//! same decision) and names the reason, and the generic route answers the refused lanes.
//!
//! Two kernels compute a chunk: [`super::pair`] for N = 2, written out on named lanes so they
//! stay in registers, and the field-generic lean code on `Lanes<L>` for every other N; both
//! perform the lean path's operations in its order ([`Kernel`]).
//!
//! The function here is generic over L and marked `#[inline(always)]`: [`super`] instantiates
//! it inside functions compiled for AVX-512 or AVX2 (chosen when the program runs), and L f64
//! of `Lanes<L>` become one register there.

use std::array;

use super::lanes::{Lanes, Mask};
use super::pair::Pair;
use super::{Outcomes, Scenes, solve_generic};
use crate::impact::lean::{Data, Factored, InverseInertia, LeanError, limit2, route_test};
use crate::impact::restitution::Model;

/// Scenes `start .. start + L` of `v` as lanes; past the end, the last scene repeated.
#[inline(always)]
pub(super) fn load<const L: usize>(v: &[f64], start: usize) -> Lanes<L> {
    match v.get(start..start + L).map(<[f64; L]>::try_from) {
        Some(Ok(chunk)) => Lanes(chunk),
        _ => {
            let last = v.len().saturating_sub(1);
            Lanes(array::from_fn(|l| v[(start + l).min(last)]))
        }
    }
}

/// x, y and z of `a` (see [`load`]).
#[inline(always)]
pub(super) fn load3<const L: usize>(a: &[Vec<f64>; 3], start: usize) -> [Lanes<L>; 3] {
    [load(&a[0], start), load(&a[1], start), load(&a[2], start)]
}

/// Scenes `start .. start + L` as lanes (see [`load`]).
#[inline(always)]
fn gather<const L: usize, const N: usize>(scenes: &Scenes<N>, start: usize) -> Data<Lanes<L>, N> {
    let v = &scenes.velocity;
    Data {
        mass: load(&scenes.mass, start),
        inertia: InverseInertia::Principal(load3(&scenes.inertia, start)),
        velocity: [
            load(&v[0], start),
            load(&v[1], start),
            load(&v[2], start),
            load(&v[3], start),
            load(&v[4], start),
            load(&v[5], start),
        ],
        points: array::from_fn(|i| load3(&scenes.points[i], start)),
        normals: array::from_fn(|i| load3(&scenes.normals[i], start)),
        k_newton: array::from_fn(|i| load(&scenes.k_newton[i], start)),
        k_poisson: array::from_fn(|i| load(&scenes.k_poisson[i], start)),
    }
}

/// Lane by lane, whether every value of `xs` is finite: |x| ≤ f64::MAX, false for ±∞ and
/// NaN. (The same decision as the lean path's Σ 0·x = 0, without its chain of dependent
/// additions.)
#[inline(always)]
pub(super) fn finite<const L: usize>(xs: &[Lanes<L>]) -> Mask<L> {
    let max = Lanes::<L>::splat(f64::MAX);
    let mut ok = Mask::all_true();
    for x in xs {
        ok &= x.test(&max, |x, m| x.abs() <= m);
    }
    ok
}

/// Which lanes of `data` pass [`crate::impact::problem::Problem::new`]'s checks
/// ([`valid_parts`]).
#[inline(always)]
fn valid<const L: usize, const N: usize>(data: &Data<Lanes<L>, N>) -> Mask<L> {
    let InverseInertia::Principal(j) = &data.inertia else {
        return Mask([0; L]);
    };
    valid_parts(
        &data.mass,
        j,
        &data.velocity,
        &data.points,
        &data.normals,
        &data.k_newton,
        &data.k_poisson,
    )
}

/// Which lanes of a scene (m, principal moments J_k, {v⁰}, r_j, n_j, k_j^N, k_j^P) pass
/// [`crate::impact::problem::Problem::new`]'s checks: m, J_k > 0, every number finite,
/// normals nonzero, k ∈ [0, 1] (decided lane by lane, without building a problem; NaN fails
/// every comparison).
#[inline(always)]
pub(super) fn valid_parts<const L: usize, const N: usize>(
    mass: &Lanes<L>,
    j: &[Lanes<L>; 3],
    velocity: &[Lanes<L>; 6],
    points: &[[Lanes<L>; 3]; N],
    normals: &[[Lanes<L>; 3]; N],
    k_newton: &[Lanes<L>; N],
    k_poisson: &[Lanes<L>; N],
) -> Mask<L> {
    let (zero, one, max) = (Lanes::splat(0.0), Lanes::splat(1.0), Lanes::splat(f64::MAX));
    let positive = |x: &Lanes<L>| x.test(&zero, |x, z| x > z) & x.test(&max, |x, m| x <= m);
    let coefficient = |x: &Lanes<L>| x.test(&zero, |x, z| x >= z) & x.test(&one, |x, o| x <= o);
    let mut ok = positive(mass) & positive(&j[0]) & positive(&j[1]) & positive(&j[2]);
    ok &= finite(velocity);
    for i in 0..N {
        let n = &normals[i];
        ok &= finite(&points[i]) & finite(n);
        ok &= coefficient(&k_newton[i]) & coefficient(&k_poisson[i]);
        let nonzero = |x: &Lanes<L>| x.test(&zero, |x, z| x != z);
        ok &= nonzero(&n[0]) | nonzero(&n[1]) | nonzero(&n[2]);
    }
    ok
}

/// Lane by lane, whether [`route_test`] accepts Ĝ's lower triangle `g` and pivots `d`: the
/// same operations in the same order, on lanes (so the same decision in every lane; NaN is
/// refused).
#[inline(always)]
fn routed<const L: usize, const N: usize>(g: &[[Lanes<L>; N]; N], d: &[Lanes<L>; N]) -> Mask<L> {
    let zero = Lanes::splat(0.0);
    let mut ok = Mask::all_true();
    for d in d {
        ok &= d.test(&zero, |d, z| d > z);
    }
    let limit = limit2::<N>();
    if N == 2 {
        let bound = Lanes::splat(1.0 - limit) * g[1][1];
        ok &= d[1].test(&bound, |d, b| d >= b);
    } else if N > 2 {
        let rows = Lanes::splat((N - 1) as f64);
        for i in 0..N {
            let mut s = Lanes::splat(0.0);
            for j in (0..N).filter(|&j| j != i) {
                let gij = if i >= j { g[i][j] } else { g[j][i] };
                s += gij * gij / g[j][j];
            }
            ok &= (rows * s / g[i][i]).test(&Lanes::splat(limit), |spread, l| spread <= l);
        }
    }
    ok
}

/// L scenes read, checked and factored, ready to solve under either model: what [`sweep`]
/// needs of a kernel.
pub(super) trait Kernel<const L: usize, const N: usize>: Sized {
    /// Scenes `start .. start + L` of `scenes` (past the end, the last repeated), read,
    /// checked and factored. An associated function rather than a closure handed to
    /// [`sweep`]: called through `Fn::call` it was not inlined into the function `pulp`
    /// compiles for AVX-512, and ran as SSE2 code outside it.
    fn read(scenes: &Scenes<N>, start: usize) -> Self;
    /// Lanes whose input is a valid problem.
    fn valid(&self) -> Mask<L>;
    /// Lanes the route test accepts (the operations of [`route_test`], on lanes).
    fn routed(&self) -> Mask<L>;
    /// The impulses P̂ and the twist after impact under `model`, every lane.
    fn solve(&self, model: Model) -> ([Lanes<L>; N], [Lanes<L>; 6]);
    /// The scalar route test on lane `l` (the same decision as [`Kernel::routed`], with the
    /// reason).
    fn route(&self, l: usize) -> Result<(), LeanError>;
}

/// The field-generic lean code on lanes, for any N.
struct Generic<const L: usize, const N: usize> {
    valid: Mask<L>,
    factored: Factored<Lanes<L>, N>,
    g: [[Lanes<L>; N]; N],
}

impl<const L: usize, const N: usize> Kernel<L, N> for Generic<L, N> {
    #[inline(always)]
    fn read(scenes: &Scenes<N>, start: usize) -> Self {
        let data = gather::<L, N>(scenes, start);
        let (factored, g) = data.factor();
        Generic {
            valid: valid(&data),
            factored,
            g,
        }
    }

    #[inline(always)]
    fn valid(&self) -> Mask<L> {
        self.valid
    }

    #[inline(always)]
    fn routed(&self) -> Mask<L> {
        routed(&self.g, self.factored.pivots())
    }

    #[inline(always)]
    fn solve(&self, model: Model) -> ([Lanes<L>; N], [Lanes<L>; 6]) {
        self.factored.solve(model)
    }

    #[inline]
    fn route(&self, l: usize) -> Result<(), LeanError> {
        let d = self.factored.pivots();
        route_test::<N>(|i, j| self.g[i][j].0[l], |j| d[j].0[l])
    }
}

/// Solve every scene of `scenes` under each model of `outs`, L at a time (module docs):
/// by [`Pair`] for two contacts, else by the generic lean code on lanes.
/// `outs` are sized for the scenes; their routes start as [`super::Route::Lean`].
#[inline(always)]
pub(super) fn sweep<const L: usize, const N: usize>(
    scenes: &Scenes<N>,
    outs: &mut [(Model, &mut Outcomes<N>)],
) {
    if N == 2 {
        sweep_with::<L, N, Pair<L>>(scenes, outs)
    } else {
        sweep_with::<L, N, Generic<L, N>>(scenes, outs)
    }
}

/// [`sweep`] by the generic lean code on lanes at every N (for the tests: [`Pair`] against it).
#[cfg(test)]
pub(super) fn sweep_generic<const L: usize, const N: usize>(
    scenes: &Scenes<N>,
    outs: &mut [(Model, &mut Outcomes<N>)],
) {
    sweep_with::<L, N, Generic<L, N>>(scenes, outs)
}

/// Every chunk of `scenes` by the kernel K, under each model of `outs`.
#[inline(always)]
fn sweep_with<const L: usize, const N: usize, K: Kernel<L, N>>(
    scenes: &Scenes<N>,
    outs: &mut [(Model, &mut Outcomes<N>)],
) {
    let n = scenes.len();
    let mut work = None;
    // (lane, model, why) of each lane a model's lean answer is refused in, per chunk.
    let mut refused: Vec<(usize, usize, LeanError)> = Vec::new();
    let mut by_scene: Vec<(usize, LeanError)> = Vec::new();
    for start in (0..n).step_by(L) {
        let kernel = K::read(scenes, start);
        let valid = kernel.valid();
        let accepted = valid & kernel.routed();
        let count = L.min(n - start);
        for (m, (model, out)) in outs.iter_mut().enumerate() {
            let (p, v) = kernel.solve(*model);
            let output_finite = valid & finite(&p) & finite(&v);
            // The common case, every lane valid and accepted: whole lanes out at once.
            if count == L && (accepted & output_finite).all() {
                let range = start..start + L;
                for (o, x) in out.impulses_hat.iter_mut().zip(&p) {
                    o[range.clone()].copy_from_slice(&x.0);
                }
                for (o, x) in out.velocity.iter_mut().zip(&v) {
                    o[range.clone()].copy_from_slice(&x.0);
                }
                continue;
            }
            for l in 0..count {
                let route = match output_finite.lane(l) {
                    true => kernel.route(l),
                    false => Err(LeanError::NotFinite),
                };
                match route {
                    Ok(()) => {
                        for (o, x) in out.impulses_hat.iter_mut().zip(&p) {
                            o[start + l] = x.0[l];
                        }
                        for (o, x) in out.velocity.iter_mut().zip(&v) {
                            o[start + l] = x.0[l];
                        }
                    }
                    Err(why) => refused.push((l, m, why)),
                }
            }
        }
        // The refused lanes by the generic route, each scene assembled once for its models.
        refused.sort_by_key(|r| (r.0, r.1));
        for lane in refused.chunk_by(|a, b| a.0 == b.0) {
            by_scene.clear();
            by_scene.extend(lane.iter().map(|(_, m, why)| (*m, why.clone())));
            solve_generic(scenes, start + lane[0].0, &by_scene, outs, &mut work);
        }
        refused.clear();
    }
}
