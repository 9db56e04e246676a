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

/// Scenes `start .. start + L` of `v` as lanes.
///
/// `WHOLE`: the caller's chunk lies inside `v` (the hot loop's whole chunks), read as one
/// vector; if it did not, every lane would be NaN, which no lane's checks accept, so the chunk
/// would go to the lane-by-lane fallback and be read again. Not `WHOLE` (the fallback, the
/// last partial chunk): past the end, the last scene repeated. The two are separate code so
/// that the hot loop's lanes are plain vector loads: a choice between the vector and a lane
/// by lane copy made LLVM build every input from pieces on the stack.
#[inline(always)]
pub(super) fn load<const L: usize, const WHOLE: bool>(v: &[f64], start: usize) -> Lanes<L> {
    let chunk = v.get(start..start + L).map(<[f64; L]>::try_from);
    match (WHOLE, chunk) {
        (_, Some(Ok(chunk))) => Lanes(chunk),
        (true, _) => Lanes::splat(f64::NAN),
        (false, _) => {
            let last = v.len().saturating_sub(1);
            Lanes(array::from_fn(|l| v[(start + l).min(last)]))
        }
    }
}

/// x, y and z of `a` (see [`load`]).
#[inline(always)]
pub(super) fn load3<const L: usize, const WHOLE: bool>(
    a: &[Vec<f64>; 3],
    start: usize,
) -> [Lanes<L>; 3] {
    [
        load::<L, WHOLE>(&a[0], start),
        load::<L, WHOLE>(&a[1], start),
        load::<L, WHOLE>(&a[2], start),
    ]
}

/// The six coordinates of {v⁰} (see [`load`]): direct calls, not a closure, which was not
/// inlined into the dispatched function.
#[inline(always)]
pub(super) fn load6<const L: usize, const WHOLE: bool>(
    a: &[Vec<f64>; 6],
    start: usize,
) -> [Lanes<L>; 6] {
    [
        load::<L, WHOLE>(&a[0], start),
        load::<L, WHOLE>(&a[1], start),
        load::<L, WHOLE>(&a[2], start),
        load::<L, WHOLE>(&a[3], start),
        load::<L, WHOLE>(&a[4], start),
        load::<L, WHOLE>(&a[5], start),
    ]
}

/// Scenes `start .. start + L` as lanes (see [`load`]).
#[inline(always)]
fn gather<const L: usize, const N: usize, const WHOLE: bool>(
    scenes: &Scenes<N>,
    start: usize,
) -> Data<Lanes<L>, N> {
    Data {
        mass: load::<L, WHOLE>(&scenes.mass, start),
        inertia: InverseInertia::Principal(load3::<L, WHOLE>(&scenes.inertia, start)),
        velocity: load6::<L, WHOLE>(&scenes.velocity, start),
        points: array::from_fn(|i| load3::<L, WHOLE>(&scenes.points[i], start)),
        normals: array::from_fn(|i| load3::<L, WHOLE>(&scenes.normals[i], start)),
        k_newton: array::from_fn(|i| load::<L, WHOLE>(&scenes.k_newton[i], start)),
        k_poisson: array::from_fn(|i| load::<L, WHOLE>(&scenes.k_poisson[i], start)),
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

/// Lane by lane, a sufficient test that every value of `xs` is finite, in one addition per
/// value: their sum is finite. An infinite or NaN term makes every sum that contains it
/// infinite or NaN (∞ + finite = ∞, ∞ − ∞ = NaN, NaN + x = NaN), so a finite sum means finite
/// terms; a lane of finite values whose sum overflows is refused, and the hot loop of
/// [`sweep_with`] then hands its chunk to the fallback, whose test ([`finite`]) is exact.
#[inline(always)]
pub(super) fn surely_finite<const L: usize>(xs: &[Lanes<L>]) -> Mask<L> {
    // Four running sums, so that the additions do not wait on one another.
    let mut sums = [Lanes::splat(0.0); 4];
    for (i, x) in xs.iter().enumerate() {
        sums[i % 4] += *x;
    }
    let sum = (sums[0] + sums[1]) + (sums[2] + sums[3]);
    sum.test(&Lanes::splat(f64::MAX), |s, m| s.abs() <= m)
}

/// Which lanes of `data` pass [`crate::impact::problem::Problem::new`]'s checks
/// ([`valid_parts`]).
#[inline(always)]
fn valid<const L: usize, const N: usize>(data: &Data<Lanes<L>, N>) -> Mask<L> {
    let InverseInertia::Principal(j) = &data.inertia else {
        return Mask([0; L]);
    };
    valid_parts::<L, N, false>(
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
/// every comparison). Exactly those lanes, or with `QUICK` a sufficient test, finiteness
/// by [`surely_finite`] (a lane it accepts is valid; it may refuse a valid lane whose values
/// add up to more than f64::MAX).
#[inline(always)]
pub(super) fn valid_parts<const L: usize, const N: usize, const QUICK: bool>(
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
    if !QUICK {
        ok &= finite(velocity);
        for i in 0..N {
            ok &= finite(&points[i]) & finite(&normals[i]);
        }
    } else {
        ok &= surely_finite(velocity)
            & surely_finite(points.as_flattened())
            & surely_finite(normals.as_flattened());
    }
    for i in 0..N {
        let n = &normals[i];
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
    /// `WHOLE`: the hot loop's whole chunk (see [`load`]).
    fn read<const WHOLE: bool>(scenes: &Scenes<N>, start: usize) -> Self;
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
    fn read<const WHOLE: bool>(scenes: &Scenes<N>, start: usize) -> Self {
        let data = gather::<L, N, WHOLE>(scenes, start);
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
///
/// The hot loop takes the whole chunks: each model's L answers are solved and written out at
/// once, and the chunk's tests — valid input, the route test, finite outputs, the first and
/// the last by sufficient tests ([`surely_finite`]) — are gathered into one mask on the way.
/// Only a chunk with a lane that fails them, and the last, partial chunk, goes to
/// [`Fallback::chunk`], which reads it again and decides lane by lane with the exact tests,
/// overwriting every lane it does not take from the lanes. Writing before deciding keeps the
/// masks' intermediates from waiting on the lanes' answers.
#[inline(always)]
fn sweep_with<const L: usize, const N: usize, K: Kernel<L, N>>(
    scenes: &Scenes<N>,
    outs: &mut [(Model, &mut Outcomes<N>)],
) {
    let n = scenes.len();
    let whole = n - n % L;
    let mut fallback = Fallback::default();
    for start in (0..whole).step_by(L) {
        let kernel = K::read::<true>(scenes, start);
        let mut ok = kernel.valid() & kernel.routed();
        for (model, out) in outs.iter_mut() {
            let (p, v) = kernel.solve(*model);
            ok &= surely_finite(&p) & surely_finite(&v);
            let range = start..start + L;
            for (o, x) in out.impulses_hat.iter_mut().zip(&p) {
                o[range.clone()].copy_from_slice(&x.0);
            }
            for (o, x) in out.velocity.iter_mut().zip(&v) {
                o[range.clone()].copy_from_slice(&x.0);
            }
        }
        if !ok.all() {
            fallback.chunk::<L, N, K>(scenes, start, outs);
        }
    }
    if whole < n {
        fallback.chunk::<L, N, K>(scenes, whole, outs);
    }
}

/// The lane-by-lane decisions for the chunks the hot loop of [`sweep_with`] cannot take whole,
/// with the buffers they reuse.
#[derive(Default)]
struct Fallback {
    /// The generic solve's buffers.
    work: super::Work,
    /// (lane, model, why) of each lane a model's lean answer is refused in.
    refused: Vec<(usize, usize, LeanError)>,
    /// (model, why) of one scene.
    by_scene: Vec<(usize, LeanError)>,
}

impl Fallback {
    /// Scenes `start .. min(start + L, n)`, lane by lane: a lane whose input is valid, whose
    /// answer is finite and which the scalar route test accepts takes the lanes' answer (the
    /// same operations as the hot loop's, hence the same bits); every other lane is zeroed and
    /// handed to the generic route, which writes its answer where it has one.
    #[cold]
    #[inline(never)]
    fn chunk<const L: usize, const N: usize, K: Kernel<L, N>>(
        &mut self,
        scenes: &Scenes<N>,
        start: usize,
        outs: &mut [(Model, &mut Outcomes<N>)],
    ) {
        let count = L.min(scenes.len() - start);
        let kernel = K::read::<false>(scenes, start);
        let valid = kernel.valid();
        for (m, (model, out)) in outs.iter_mut().enumerate() {
            let (p, v) = kernel.solve(*model);
            let output_finite = valid & finite(&p) & finite(&v);
            for l in 0..count {
                let route = match output_finite.lane(l) {
                    true => kernel.route(l),
                    false => Err(LeanError::NotFinite),
                };
                let taken = route.is_ok();
                for (o, x) in out.impulses_hat.iter_mut().zip(&p) {
                    o[start + l] = if taken { x.0[l] } else { 0.0 };
                }
                for (o, x) in out.velocity.iter_mut().zip(&v) {
                    o[start + l] = if taken { x.0[l] } else { 0.0 };
                }
                if let Err(why) = route {
                    self.refused.push((l, m, why));
                }
            }
        }
        // The refused lanes by the generic route, each scene assembled once for its models.
        self.refused.sort_by_key(|r| (r.0, r.1));
        for lane in self.refused.chunk_by(|a, b| a.0 == b.0) {
            self.by_scene.clear();
            self.by_scene
                .extend(lane.iter().map(|(_, m, why)| (*m, why.clone())));
            solve_generic(
                scenes,
                start + lane[0].0,
                &self.by_scene,
                outs,
                &mut self.work,
            );
        }
        self.refused.clear();
    }
}
