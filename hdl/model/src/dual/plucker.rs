//! The Plücker filter (docs/precision.md, "The Plücker filter"): det and the numerators of
//! u, v, t as dot products of per-ray and per-triangle block vectors, so a test needs no
//! translation and no conversion from fp32, only 27 integer products at W = 18. With
//! s = orig − v0, n = e1 × e2, e3 = v2 − v1 and the ray's moment m = orig × dir:
//! - det = e1·(dir × e2) = −dir·n;
//! - N_u = s·(dir × e2) = −((−e2)·m + dir·(−(v0 × e2)));
//! - N_v = dir·(s × e1) = −(e1·m + dir·(v0 × e1));
//! - N_w = det − N_u − N_v = −(e3·m + dir·(v1 × e3));
//! - N_t = e2·(s × e1) = −((−orig)·n + v0·n).
//!
//! Per ray the filter holds dir, m and −orig, per triangle n, e1, −e2, e3, v0 × e1,
//! −(v0 × e2), v1 × e3, v0 and the scalar ṽ0·ñ of v0's and n's stored blocks. Each vector is
//! formed exactly from the fp32 coordinates and stored as a block ([`Block`]): W-bit
//! mantissas, each the floor of its component on one grid. The stored signs make the
//! datapath's five values ([`datapath`]) the negatives of det, N_u, N_v, N_w, N_t, which the
//! decisions take as they are (σ = sign(det) flips with them, σN does not). Every value is
//! an exact integer, a sum of two dots floored onto the coarser grid ([`align_add`]).
//!
//! The margins ([`decide_inputs`]) are integers in units of a value's last bit, as the bfp
//! filter's are: each dot's bound a wired constant shifted by its grid's distance below the
//! value's, the alignment's unit, and the fp32 fallback's bound (`bfp::fallback_constant`)
//! shifted by the distance of 2^ΣE from the value's last bit, ΣE from block exponents and
//! the exponent of |s| that a coarse subtraction gives ([`s_exponent`]). The values are
//! fitted to the widths of the bfp filter's step 5 (`bfp::decide`, `Decide` in rust-hdl),
//! which the sign decisions (`signs::decide`, [`certain_miss`]) take with N_w and its own
//! margin ([`sign_inputs`]): bit for bit what the hardware lane computes.

use std::ops::RangeInclusive;

use sw_renderer::intersect::MtQuery;

use super::bfp::{
    self, constant, fallback_constant, lsb_range, margin_bits, split, top, value_bits, Fx, Term,
    Vector, DET, EXP_MAX, EXP_MIN, N_T, N_U, N_V, SUM_MIN,
};
use super::signs;

/// Block exponents a stored vector may have (a 10-bit biased field in hardware); outside,
/// the query is forwarded.
pub const EXP_RANGE: RangeInclusive<i32> = -128..=127;

/// Extra mantissa bits of the t test's vectors, orig, v0 and n (25 bits at W = 18, a
/// DSP48E1's wide port): N_t = orig·n − v0·n cancels when a ray starts near a triangle's
/// plane, as spawned rays do beside the surface they leave, and at W bits the t test
/// decided almost none of the queries whose ray line passes inside the edges behind the
/// origin.
pub const T_EXTRA_BITS: u32 = 7;

/// The width of the t test's vectors (orig, v0 and n) in a `bfpW` Plücker filter.
pub const fn wide(width: u32) -> u32 {
    width + T_EXTRA_BITS
}

/// The width of the stored ṽ0·ñ: the exact dot of two [`wide`] blocks.
pub const fn offset_bits(width: u32) -> u32 {
    2 * wide(width) + 1
}

/// Bits of v0's cut, the coarse copy of v0 from which [`s_exponent`] bounds |s|.
pub const S_BOUND_BITS: u32 = 9;

/// A dot's bound in units of its last bit, for a- and b-bit blocks: with ã, b̃ the stored
/// vectors (|ã_k| ≤ 2^E_a, each within one step below a_k), |ã·b̃ − a·b| ≤ Σ_k |ã_k|·|b̃_k −
/// b_k| + |b_k|·|ã_k − a_k| < 3(2^E_a·2^L_b + 2^E_b·2^L_a) = 3(2^(a−1) + 2^(b−1)) units of
/// 2^(L_a + L_b).
pub const fn dot_bound(a: u32, b: u32) -> i128 {
    3 * ((1 << (a - 1)) + (1 << (b - 1)))
}

/// An exact vector.
type V3 = [Fx; 3];

fn mul(a: Fx, b: Fx) -> Option<Fx> {
    Some(Fx::new(a.m.checked_mul(b.m)?, a.e + b.e))
}

fn sub(a: Fx, b: Fx) -> Option<Fx> {
    a.checked_add(Fx::new(-b.m, b.e))
}

fn neg(v: V3) -> V3 {
    v.map(|x| Fx::new(-x.m, x.e))
}

fn difference(a: V3, b: V3) -> Option<V3> {
    Some([sub(a[0], b[0])?, sub(a[1], b[1])?, sub(a[2], b[2])?])
}

/// a × b exactly; `None` if an intermediate leaves i128.
fn cross(a: V3, b: V3) -> Option<V3> {
    let c = |j: usize, k: usize| sub(mul(a[j], b[k])?, mul(a[k], b[j])?);
    Some([c(1, 2)?, c(2, 0)?, c(0, 1)?])
}

/// x floored onto the grid 2^lsb (an arithmetic shift).
fn floor_at(x: Fx, lsb: i32) -> i128 {
    if x.m == 0 {
        return 0;
    }
    match x.e - lsb {
        up @ 0.. => x.m << up,
        down => x.m >> (-down).min(127),
    }
}

/// A stored vector: N mantissas of `width` two's-complement bits on the grid 2^`lsb`, the
/// block exponent E = lsb + width − 1 the smallest with every exact component in
/// [−2^E, 2^E), each mantissa the floor of its component (within one step below it).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Block<const N: usize> {
    m: [i128; N],
    lsb: i32,
    width: u32,
}

impl Block<3> {
    /// `None` if E leaves [`EXP_RANGE`]; the zero vector takes its low end.
    fn of(v: V3, width: u32) -> Option<Block<3>> {
        let e = v
            .iter()
            .filter(|x| x.m != 0)
            .map(|&x| top(x))
            .max()
            .unwrap_or(*EXP_RANGE.start());
        if !EXP_RANGE.contains(&e) {
            return None;
        }
        let lsb = e - (width as i32 - 1);
        Some(Block {
            m: v.map(|x| floor_at(x, lsb)),
            lsb,
            width,
        })
    }
}

impl<const N: usize> Block<N> {
    fn bits(&self) -> BlockBits<N> {
        BlockBits {
            m: self.m.map(|m| m as i64),
            lsb: self.lsb,
        }
    }
}

/// A stored vector as hardware reads it: the mantissas and the exponent of their last bit.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct BlockBits<const N: usize> {
    pub m: [i64; N],
    pub lsb: i32,
}

/// What the filter holds of a ray.
struct Ray {
    dir: Block<3>,
    moment: Block<3>,
    /// −orig, at [`wide`] bits.
    orig: Block<3>,
}

impl Ray {
    fn new(orig: V3, dir: V3, width: u32) -> Option<Ray> {
        Some(Ray {
            dir: Block::of(dir, width)?,
            moment: Block::of(cross(orig, dir)?, width)?,
            orig: Block::of(neg(orig), wide(width))?,
        })
    }
}

/// What the filter holds of a triangle.
struct Triangle {
    /// n = e1 × e2 at [`wide`] bits.
    n: Block<3>,
    /// e1, −e2, e3 = v2 − v1.
    edges: [Block<3>; 3],
    /// v0 × e1, −(v0 × e2), v1 × e3.
    moments: [Block<3>; 3],
    /// v0 at [`wide`] bits; hardware stores ṽ0·ñ and v0's cut ([`S_BOUND_BITS`]).
    v0: Block<3>,
    /// ṽ0·ñ exactly, [`offset_bits`] wide.
    offset: Block<1>,
}

impl Triangle {
    fn new(v0: V3, v1: V3, v2: V3, width: u32) -> Option<Triangle> {
        let (e1, e2, e3) = (
            difference(v1, v0)?,
            difference(v2, v0)?,
            difference(v2, v1)?,
        );
        let (n, v0_block) = (
            Block::of(cross(e1, e2)?, wide(width))?,
            Block::of(v0, wide(width))?,
        );
        Some(Triangle {
            offset: Block {
                m: [bfp::dot(&v0_block.m, &n.m)],
                lsb: v0_block.lsb + n.lsb,
                width: offset_bits(width),
            },
            n,
            edges: [
                Block::of(e1, width)?,
                Block::of(neg(e2), width)?,
                Block::of(e3, width)?,
            ],
            moments: [
                Block::of(cross(v0, e1)?, width)?,
                Block::of(neg(cross(v0, e2)?), width)?,
                Block::of(cross(v1, e3)?, width)?,
            ],
            v0: v0_block,
        })
    }

    /// v0's cut: its top [`S_BOUND_BITS`] bits (floors compose: cut further, it is v0's
    /// block floored).
    fn v0_cut(&self) -> BlockBits<3> {
        let drop = self.v0.width - S_BOUND_BITS;
        BlockBits {
            m: self.v0.m.map(|m| (m >> drop) as i64),
            lsb: self.v0.lsb + drop as i32,
        }
    }
}

/// The exponent E_s with every |s_k| = |orig_k − v0_k| ≤ 2^E_s, from −orig's block (`orig`,
/// [`wide`]`(width)` bits) and v0's cut, as hardware forms it: both floored onto the grid
/// G = max(E_orig, E_v0) − [`S_BOUND_BITS`] + 1 and added to c_k; each stored value is within
/// one step (≤ 2^G) below its exact one and each floor within 2^G below, so −s_k lies in
/// [c_k·2^G, (c_k + 4)·2^G), and |s_k| ≤ (|c_k + 2| + 2)·2^G ≤ B·2^G ≤ 2^(G + ⌈log₂B⌉) for
/// B = max_k |c_k + 2| + 2.
pub fn s_exponent(orig: &BlockBits<3>, v0_cut: &BlockBits<3>, width: u32) -> i32 {
    let e_orig = orig.lsb + wide(width) as i32 - 1;
    let e_v0 = v0_cut.lsb + S_BOUND_BITS as i32 - 1;
    let g = e_orig.max(e_v0) - (S_BOUND_BITS as i32 - 1);
    let at = |m: i64, lsb: i32| m >> (g - lsb).min(63);
    let b = (0..3)
        .map(|k| (at(orig.m[k], orig.lsb) + at(v0_cut.m[k], v0_cut.lsb) + 2).abs() + 2)
        .max()
        .expect("three components");
    g + (64 - (b - 1).leading_zeros()) as i32
}

/// A value of the datapath: `fx` in `bits` two's-complement bits, with what bounds its
/// distance from the exact value: each dot's grid and bound ([`dot_bound`]; the second 0
/// for a single dot; a sum of two dots is floored onto the coarser grid, one unit more).
#[derive(Clone, Copy, Debug)]
struct Value {
    fx: Fx,
    bits: u32,
    dots: [(i32, i128); 2],
}

fn dot(a: &Block<3>, b: &Block<3>) -> Value {
    let lsb = a.lsb + b.lsb;
    Value {
        fx: Fx::new(bfp::dot(&a.m, &b.m), lsb),
        bits: a.width + b.width + 1,
        dots: [(lsb, dot_bound(a.width, b.width)), (lsb, 0)],
    }
}

/// x + y of two single dots as a hardware adder takes them ([`align_add`]).
fn combine(x: Value, y: Value) -> Value {
    let (fx, bits) = align_add((x.fx, x.bits), (y.fx, y.bits));
    Value {
        fx,
        bits,
        dots: [x.dots[0], y.dots[0]],
    }
}

/// The sum of two N-bit two's-complement values a·2^ea and b·2^eb on the coarser grid: the
/// finer shifted right arithmetically by the exponent difference, at most N − 1 (beyond, it
/// is its sign, 0 or −1, either way), so the sum is floor-truncated, below the exact one by
/// less than one unit; N + 1 bits, N the wider operand's width.
pub fn align_add((a, a_bits): (Fx, u32), (b, b_bits): (Fx, u32)) -> (Fx, u32) {
    let n = a_bits.max(b_bits);
    let (coarse, fine) = if a.e >= b.e { (a, b) } else { (b, a) };
    let shift = (coarse.e - fine.e).min(n as i32 - 1);
    (Fx::new(coarse.m + (fine.m >> shift), coarse.e), n + 1)
}

/// The datapath's values from the stored vectors: dir·n, (−e2)·m + dir·(−(v0 × e2)),
/// e1·m + dir·(v0 × e1), e3·m + dir·(v1 × e3), (−orig)·n + ṽ0·ñ; that is −det, −N_u, −N_v,
/// −N_w, −N_t.
fn values_of(ray: &Ray, tri: &Triangle) -> [Value; 5] {
    let edge = |k: usize| {
        combine(
            dot(&tri.edges[k], &ray.moment),
            dot(&ray.dir, &tri.moments[k]),
        )
    };
    let offset = Value {
        fx: Fx::new(tri.offset.m[0], tri.offset.lsb),
        bits: tri.offset.width,
        dots: [
            (tri.offset.lsb, dot_bound(tri.v0.width, tri.n.width)),
            (tri.offset.lsb, 0),
        ],
    };
    [
        dot(&ray.dir, &tri.n),
        edge(1),
        edge(0),
        edge(2),
        combine(dot(&ray.orig, &tri.n), offset),
    ]
}

/// What the datapath reads for one test: the ray's stored vectors (dir, m = orig × dir at W
/// bits, −orig at [`wide`]) and the triangle's (n at [`wide`], e1, −e2, e3 and v0 × e1,
/// −(v0 × e2), v1 × e3 at W bits, ṽ0·ñ at [`offset_bits`], v0's cut at [`S_BOUND_BITS`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Operands {
    pub dir: BlockBits<3>,
    pub moment: BlockBits<3>,
    pub orig: BlockBits<3>,
    pub n: BlockBits<3>,
    pub edges: [BlockBits<3>; 3],
    pub moments: [BlockBits<3>; 3],
    pub offset: BlockBits<1>,
    pub v0_cut: BlockBits<3>,
}

/// The block exponents the fallback's bound is evaluated on: every |dir_k| ≤ 2^`dir`,
/// |e1_k| ≤ 2^`e1`, |e2_k| ≤ 2^`e2` (−e2's block exponent: at most one more than e2's),
/// |s_k| ≤ 2^`s` ([`s_exponent`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct FallbackExps {
    pub dir: i32,
    pub e1: i32,
    pub e2: i32,
    pub s: i32,
}

impl FallbackExps {
    /// From the operands, as hardware has them.
    pub fn of(ops: &Operands, width: u32) -> FallbackExps {
        let e = |b: &BlockBits<3>| b.lsb + width as i32 - 1;
        FallbackExps {
            dir: e(&ops.dir),
            e1: e(&ops.edges[0]),
            e2: e(&ops.edges[1]),
            s: s_exponent(&ops.orig, &ops.v0_cut, width),
        }
    }

    /// ΣE of det, N_u, N_v, N_t: the exponent sums of bfp's [`DET`], [`N_U`], [`N_V`],
    /// [`N_T`].
    pub fn sums(&self) -> [i32; 4] {
        let FallbackExps { dir, e1, e2, s } = *self;
        [e1 + dir + e2, s + dir + e2, dir + s + e1, e2 + s + e1]
    }

    /// Inside the range the fallback constant covers (`bfp::fallback_constant`): each
    /// exponent in [`EXP_MIN`, `EXP_MAX`], each sum at least [`SUM_MIN`].
    pub fn covered(&self) -> bool {
        [self.dir, self.e1, self.e2, self.s]
            .iter()
            .all(|e| (EXP_MIN..=EXP_MAX).contains(e))
            && self.sums().iter().all(|&s| s >= SUM_MIN)
    }
}

/// The ray's and the triangle's stored vectors for `q`; `None` for a non-finite coordinate,
/// an exact vector beyond i128 or a block exponent outside [`EXP_RANGE`] (the filter
/// forwards such a query).
fn stored(q: &MtQuery, width: u32) -> Option<(Ray, Triangle)> {
    let exact = |p: [f32; 3]| -> Option<V3> { Some([split(p[0])?, split(p[1])?, split(p[2])?]) };
    Some((
        Ray::new(exact(q.orig)?, exact(q.dir)?, width)?,
        Triangle::new(exact(q.v0)?, exact(q.v1)?, exact(q.v2)?, width)?,
    ))
}

fn operands(ray: &Ray, tri: &Triangle) -> Operands {
    Operands {
        dir: ray.dir.bits(),
        moment: ray.moment.bits(),
        orig: ray.orig.bits(),
        n: tri.n.bits(),
        edges: tri.edges.map(|b| b.bits()),
        moments: tri.moments.map(|b| b.bits()),
        offset: tri.offset.bits(),
        v0_cut: tri.v0_cut(),
    }
}

/// The Plücker datapath of a `bfpW` filter, bit for bit what hardware computes: the
/// operands of `q` and the five values ([`values_of`]: −det, −N_u, −N_v, −N_w, −N_t), each
/// an exact integer on its grid; `None` where the filter forwards before any arithmetic.
pub fn datapath(q: &MtQuery, width: u32) -> Option<(Operands, [Fx; 5])> {
    let (ray, tri) = stored(q, width)?;
    Some((operands(&ray, &tri), values_of(&ray, &tri).map(|v| v.fx)))
}

/// The fallback's term of a margin: `bfp::fallback_constant` wired to
/// `bfp::CONSTANT_BITS` significant bits, times 2^ΣE.
pub fn fallback_term() -> Term {
    let c = constant(fallback_constant(), 0);
    Term { m: c.m, shift: c.e }
}

/// A value at step 5's input for its `kind` (bfp's [`DET`] for det, [`N_U`] for the
/// numerators, whose widths `Decide` takes): the value floored by k = its width − the
/// kind's ([`value_bits`]; 0 if narrower, sign-extended), and its margin in units of the
/// new last bit L as hardware wires it: the value's [`MarginConstants`] `c` (its fixed part,
/// and the finer dot's bound C·2^(L_fine − L) rounded up) and the fallback's term
/// C_F·2^(ΣE − L) rounded up (`sum_e` = ΣE). `None` (forwarded) if L is outside what step 5
/// receives from bfp ([`lsb_range`]) or the fallback's term reaches 2^(MB − 1), MB the kind's
/// [`margin_bits`] (an exponent comparison in hardware; the dots' part stays below
/// 2^(MB − 2), so the margin fits MB bits). `margin_scale` scales the margin (1: the derived
/// bound; tests shrink it).
fn fitted(
    v: &Value,
    c: MarginConstants,
    kind: [Vector; 4],
    sum_e: i32,
    width: u32,
    margin_scale: f64,
) -> Option<(Fx, i128)> {
    let k = v.bits.saturating_sub(value_bits(width, kind));
    let lsb = v.fx.e + k as i32;
    if !lsb_range(width, kind).contains(&lsb) {
        return None;
    }
    let f = fallback_term();
    let f_top = f.shift + sum_e - lsb + (128 - f.m.leading_zeros()) as i32;
    if f_top >= margin_bits(width, kind) as i32 {
        return None;
    }
    let units = dots_units(v, c, lsb) + f.units(lsb - sum_e)?;
    Some((Fx::new(v.fx.m >> k, lsb), scaled(units, margin_scale)))
}

/// A value's dots-and-alignment part of its margin on the grid 2^`lsb` (at or above its
/// own): `c`'s fixed part and the finer dot's bound at its distance below `lsb`, rounded up.
fn dots_units(v: &Value, c: MarginConstants, lsb: i32) -> i128 {
    let fine = v.dots.iter().map(|d| d.0).min().expect("two grids");
    c.fixed
        + Term {
            m: c.fine,
            shift: 0,
        }
        .units(lsb - fine)
        .expect("a right shift")
}

/// A margin scaled by `margin_scale` (1: the derived bound; tests shrink it), rounded up;
/// exact at 1 (a margin is below 2^MB ≤ 2^53).
fn scaled(units: i128, margin_scale: f64) -> i128 {
    (units as f64 * margin_scale).ceil() as i128
}

/// What a hardware margin wires for one value. Both dots of a sum have the same bound C
/// (W × W for the edges, wide × wide for N_t), so the coarser's term is a constant on the
/// fitted grid and only the finer's shifts: the margin is `fixed` + ceil(`fine`·2^-b) +
/// the fallback's term, b the finer dot's distance below the fitted last bit.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct MarginConstants {
    /// ceil(C·2^-k) of the coarser (or only) dot, k the floor onto step 5's width, plus the
    /// units: one for a floored sum, one for k > 0.
    pub fixed: i128,
    /// The finer dot's C (0: a single dot).
    pub fine: i128,
}

/// The margin constants of −det, −N_u, −N_v, −N_t at width W, which [`fitted`] charges
/// (a test checks them against each value's own dot bounds and units).
pub fn margin_constants(width: u32) -> [MarginConstants; 4] {
    let (w, wt) = (width, wide(width));
    let k = |bits: u32, kind| bits.saturating_sub(value_bits(width, kind)) as i32;
    let up = |c: i128, k: i32| Term { m: c, shift: 0 }.units(k).expect("a right shift");
    let sum = |c: i128, bits: u32, kind| {
        let k = k(bits, kind);
        MarginConstants {
            fixed: up(c, k) + 1 + i128::from(k > 0),
            fine: c,
        }
    };
    let det_k = k(w + wt + 1, DET);
    let edge = sum(dot_bound(w, w), 2 * w + 2, N_U);
    [
        MarginConstants {
            fixed: up(dot_bound(w, wt), det_k) + i128::from(det_k > 0),
            fine: 0,
        },
        edge,
        edge,
        sum(dot_bound(wt, wt), offset_bits(width) + 1, N_T),
    ]
}

/// Step 5's inputs of a `bfpW` Plücker filter: −det, −N_u, −N_v, −N_t, each fitted with its
/// margin ([`fitted`]); `None` forwards the query (before any arithmetic, as [`datapath`];
/// or the fallback's exponents outside the range its constant covers,
/// [`FallbackExps::covered`]; or a value's grid or margin out of step 5's reach).
pub fn decide_inputs(q: &MtQuery, width: u32, margin_scale: f64) -> Option<[(Fx, i128); 4]> {
    sign_inputs(q, width, margin_scale).map(|i| i.values)
}

/// What the sign decisions take: [`decide_inputs`]' values and −N_w on its own grid with
/// its own margin (its dots and alignment: the fallback does not compute N_w, and nothing
/// is fitted).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SignInputs {
    pub values: [(Fx, i128); 4],
    pub w: (Fx, i128),
}

/// [`SignInputs`] of `q`; `None` exactly where [`decide_inputs`] is.
pub fn sign_inputs(q: &MtQuery, width: u32, margin_scale: f64) -> Option<SignInputs> {
    let (ray, tri) = stored(q, width)?;
    let exps = FallbackExps::of(&operands(&ray, &tri), width);
    if !exps.covered() {
        return None;
    }
    let [det, nu, nv, nw, nt] = values_of(&ray, &tri);
    let [sd, su, sv, st] = exps.sums();
    let [cd, cu, cv, ct] = margin_constants(width);
    let fit = |v: &Value, c, kind, sum_e| fitted(v, c, kind, sum_e, width, margin_scale);
    Some(SignInputs {
        values: [
            fit(&det, cd, DET, sd)?,
            fit(&nu, cu, N_U, su)?,
            fit(&nv, cv, N_V, sv)?,
            fit(&nt, ct, N_T, st)?,
        ],
        // The third edge has the others' constants.
        w: (nw.fx, scaled(dots_units(&nw, cu, nw.fx.e), margin_scale)),
    })
}

/// Whether the Plücker filter of `width` decides `q` a certain miss: the sign decisions
/// (`signs::decide`) on [`sign_inputs`], bit for bit what the hardware lane decides.
pub fn certain_miss(q: &MtQuery, width: u32, margin_scale: f64) -> bool {
    sign_inputs(q, width, margin_scale).is_some_and(|SignInputs { values, w }| {
        let [det, nu, nv, nt] = values;
        signs::decide(det, [nu, nv, nt], w, q.t_min, width).miss()
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn coordinate() -> impl Strategy<Value = f32> {
        prop_oneof![
            1 => Just(0.0f32),
            10 => -1000.0f32..1000.0,
            3 => -1e-3f32..1e-3,
        ]
    }

    fn vector() -> impl Strategy<Value = [f32; 3]> {
        proptest::array::uniform3(coordinate())
    }

    fn exact(v: [f32; 3]) -> V3 {
        v.map(|x| split(x).unwrap())
    }

    /// A sum of two dots (each with a bound) is floored onto the coarser grid.
    fn aligned(v: &Value) -> bool {
        v.dots[1].1 != 0
    }

    /// A value's distance bound from its exact value in f64: its dots' bounds and the
    /// alignment's unit.
    fn bound(v: &Value) -> f64 {
        let dots: f64 = v.dots.iter().map(|&(l, c)| c as f64 * 2f64.powi(l)).sum();
        dots + if aligned(v) { 2f64.powi(v.fx.e) } else { 0.0 }
    }

    /// |a − b| ≤ err, checked through their f64 difference with its own rounding.
    fn within(a: f64, b: f64, err: f64) -> bool {
        (a - b).abs() <= err + (a.abs() + b.abs()) * f64::EPSILON
    }

    /// a × b in f64 (the reference): products of an f32 and an f64 difference of f32s.
    fn cross_f64(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
        std::array::from_fn(|i| {
            let (j, k) = ((i + 1) % 3, (i + 2) % 3);
            a[j] * b[k] - a[k] * b[j]
        })
    }

    fn query(orig: [f32; 3], dir: [f32; 3], v0: [f32; 3], v1: [f32; 3], v2: [f32; 3]) -> MtQuery {
        MtQuery {
            orig,
            dir,
            v0,
            v1,
            v2,
            t_min: 0.0,
        }
    }

    proptest! {
        /// A stored vector's mantissas fit W signed bits, E is the smallest exponent with
        /// every component in [−2^E, 2^E), and each mantissa is the floor of its component.
        #[test]
        fn blocks_floor_onto_the_smallest_grid(v in vector(), w in 8u32..=25) {
            let b = Block::of(exact(v), w).unwrap();
            let (step, top) = (2f64.powi(b.lsb), 2f64.powi(b.lsb + w as i32 - 1));
            for (k, x) in v.iter().map(|&x| f64::from(x)).enumerate() {
                prop_assert!((-(1i128 << (w - 1))..1 << (w - 1)).contains(&b.m[k]));
                prop_assert!((-top..top).contains(&x));
                let below = x - b.m[k] as f64 * step;
                prop_assert!((0.0..step).contains(&below), "{} {}", x, below);
            }
            if v.iter().any(|&x| x != 0.0) {
                prop_assert!(v.iter().any(|&x| f64::from(x) < -top / 2.0 || f64::from(x) >= top / 2.0));
            }
        }

        /// The alignment floors: the sum on the coarser grid is at most the exact sum and
        /// less than one unit below it, in N + 1 bits.
        #[test]
        fn align_add_floors_onto_the_coarser_grid(
            a in -(1i128 << 36)..(1i128 << 36), b in -(1i128 << 36)..(1i128 << 36),
            ea in -40i32..40, eb in -40i32..40,
        ) {
            let (sum, bits) = align_add((Fx::new(a, ea), 37), (Fx::new(b, eb), 37));
            prop_assert_eq!(bits, 38);
            prop_assert_eq!(sum.e, ea.max(eb));
            prop_assert!(sum.m >= -(1i128 << 37) && sum.m < 1i128 << 37);
            let low = ea.min(eb);
            let exact = (a << (ea - low)) + (b << (eb - low));
            let got = sum.m << (sum.e - low);
            prop_assert!(got <= exact && exact - got < 1i128 << (sum.e - low), "{} {}", got, exact);
        }

        /// E_s bounds every |orig_k − v0_k|, and is at most 2 above the smallest exponent
        /// that does, or at the cut's resolution (G + 3).
        #[test]
        fn the_s_exponent_bounds_s(orig in vector(), v0 in vector(), w in 8u32..=24) {
            let ray = Ray::new(exact(orig), exact([1.0, 0.0, 0.0]), w).unwrap();
            let tri = Triangle::new(exact(v0), exact([1.0; 3]), exact([2.0, 1.0, 1.0]), w).unwrap();
            let e = s_exponent(&ray.orig.bits(), &tri.v0_cut(), w);
            let s = (0..3).map(|k| (f64::from(orig[k]) - f64::from(v0[k])).abs()).fold(0.0, f64::max);
            prop_assert!(s <= 2f64.powi(e), "|s| {} > 2^{}", s, e);
            let top = |b: &Block<3>| b.lsb + b.width as i32 - 1;
            let g = top(&ray.orig).max(top(&tri.v0)) - (S_BOUND_BITS as i32 - 1);
            prop_assert!(e <= (g + 3).max(s.log2().floor() as i32 + 3), "{} {}", e, s);
        }

        /// The identities and the dot bounds: the datapath's values are within their
        /// bounds of −det, −N_u, −N_v, −N_w, −N_t computed the Möller-Trumbore way in f64
        /// (exact within f64's few roundings for these inputs).
        #[test]
        fn plucker_values_are_within_their_bounds(
            orig in vector(), dir in vector(), v0 in vector(), v1 in vector(), v2 in vector(),
            w in 8u32..=24,
        ) {
            let ray = Ray::new(exact(orig), exact(dir), w).unwrap();
            let tri = Triangle::new(exact(v0), exact(v1), exact(v2), w).unwrap();
            let f = |v: [f32; 3]| v.map(f64::from);
            let (orig, dir, v0, v1, v2) = (f(orig), f(dir), f(v0), f(v1), f(v2));
            let sub = |a: [f64; 3], b: [f64; 3]| -> [f64; 3] { std::array::from_fn(|k| a[k] - b[k]) };
            let dotf = |a: [f64; 3], b: [f64; 3]| (a[0] * b[0] + a[1] * b[1]) + a[2] * b[2];
            let abs = |a: [f64; 3]| a.map(f64::abs);
            let (e1, e2, s) = (sub(v1, v0), sub(v2, v0), sub(orig, v0));
            let (p, q) = (cross_f64(dir, e2), cross_f64(s, e1));
            let want_det = dotf(e1, p);
            let want = [want_det, -want_det, dotf(s, p), dotf(dir, q), 0.0, dotf(e2, q)];
            let (want_nu, want_nv, want_nt) = (want[2], want[3], want[5]);
            let want_nw = want_det - want_nu - want_nv;
            // f64's own error of the reference.
            let slack = 1e-14 * (dotf(abs(e1), abs(p)) + dotf(abs(s), abs(p))
                + dotf(abs(dir), abs(q)) + dotf(abs(e2), abs(q))) + 1e-300;
            let got = values_of(&ray, &tri).map(|v| (v.fx.to_f64(), bound(&v)));
            for (name, (v, err), exact) in [
                ("det", got[0], -want_det),
                ("N_u", got[1], -want_nu),
                ("N_v", got[2], -want_nv),
                ("N_w", got[3], -want_nw),
                ("N_t", got[4], -want_nt),
            ] {
                let slack = if name == "N_w" { 3.0 * slack } else { slack };
                prop_assert!(within(v, exact, err + slack), "{}: {} {} {}", name, v, exact, err);
            }
        }

        /// A fitted value's margin covers its floor and its bound: step 5's value is within
        /// its margin's dots-and-alignment part of the datapath's value, which is within its
        /// own bound.
        #[test]
        fn fitted_values_keep_their_distance_in_the_margin(
            orig in vector(), dir in vector(), v0 in vector(), v1 in vector(), v2 in vector(),
        ) {
            let q = query(orig, dir, v0, v1, v2);
            let Some(inputs) = decide_inputs(&q, 18, 1.0) else { return Ok(()) };
            let (ray, tri) = stored(&q, 18).unwrap();
            let [det, nu, nv, _, nt] = values_of(&ray, &tri);
            for ((fx, margin), v) in inputs.iter().zip([det, nu, nv, nt]) {
                let (a, b) = (fx.to_f64(), v.fx.to_f64());
                let unit = 2f64.powi(fx.e);
                prop_assert!(a <= b && b - a < unit, "{} {}", a, b);
                prop_assert!(bound(&v) + (b - a) <= *margin as f64 * unit * (1.0 + 1e-12));
            }
        }
    }

    proptest! {
        /// The u + v row's argument on real values: n_u − e_u + n_v − e_v − (|det| + e_D)
        /// ≥ −(n_w + M_w), from det = N_u + N_v + N_w exactly and each fitted value within
        /// its margin (which includes its own error) of the exact one.
        #[test]
        fn the_uv_margin_covers_the_identity(
            orig in vector(), dir in vector(), v0 in vector(), v1 in vector(), v2 in vector(),
        ) {
            let q = query(orig, dir, v0, v1, v2);
            let Some(SignInputs { values: [det, nu, nv, _], w }) = sign_inputs(&q, 18, 1.0) else {
                return Ok(());
            };
            let others = [(det.1, det.0.e), (nu.1, nu.0.e), (nv.1, nv.0.e)];
            let Some(m_w) = signs::uv_margin(w.1, w.0.e, others, 18) else { return Ok(()) };
            let sigma = det.0.m.signum();
            prop_assume!(sigma != 0);
            let at = |m: i128, e: i32| Fx::new(m, e);
            let sum = |xs: &[Fx]| xs.iter().try_fold(Fx::new(0, 0), |a, &x| a.checked_add(x));
            let lhs = sum(&[
                at(sigma * nu.0.m - nu.1, nu.0.e),
                at(sigma * nv.0.m - nv.1, nv.0.e),
                at(-det.0.m.abs() - det.1, det.0.e),
            ]);
            let rhs = at(-(sigma * w.0.m + m_w), w.0.e);
            if let Some(lhs) = lhs {
                prop_assert!(!lhs.lt(rhs), "{:?} < {:?}", lhs, rhs);
            }
        }
    }

    proptest! {
        /// The wired constants charge each value its own bound: each dot's bound on the
        /// fitted grid rounded up, a unit for a floored sum and one for a floor, equal to the
        /// fixed part and the finer dot's bound at its distance below the fitted last bit.
        #[test]
        fn margin_constants_are_the_values_own(
            orig in vector(), dir in vector(), v0 in vector(), v1 in vector(), v2 in vector(),
            w in 8u32..=24,
        ) {
            let ray = Ray::new(exact(orig), exact(dir), w).unwrap();
            let tri = Triangle::new(exact(v0), exact(v1), exact(v2), w).unwrap();
            let [det, nu, nv, _, nt] = values_of(&ray, &tri);
            let kinds = [DET, N_U, N_V, N_T];
            for ((v, kind), c) in [det, nu, nv, nt].iter().zip(kinds).zip(margin_constants(w)) {
                let k = v.bits.saturating_sub(value_bits(w, kind)) as i32;
                let lsb = v.fx.e + k;
                let up = |(l, c): (i32, i128)| Term { m: c, shift: 0 }.units(lsb - l).unwrap();
                let charged = up(v.dots[0]) + up(v.dots[1]) + i128::from(aligned(v)) + i128::from(k > 0);
                let fine = v.dots.iter().map(|d| d.0).min().unwrap();
                let wired = c.fixed + Term { m: c.fine, shift: 0 }.units(lsb - fine).unwrap();
                prop_assert_eq!(charged, wired, "W = {}", w);
            }
        }
    }

    /// The dots' part of every margin stays below 2^(MB − 2) at every width, so a margin
    /// whose fallback term is below 2^(MB − 1) fits MB bits.
    #[test]
    fn dot_parts_fit_their_margins() {
        for w in bfp::WIDTHS {
            let fits = |a: u32, b: u32, kind: [Vector; 4], bits: u32| {
                let k = bits.saturating_sub(value_bits(w, kind));
                // Each dot's term rounded up at a distance ≥ k, the alignment's unit and k's.
                let part = 2 * ((dot_bound(a, b) >> k) + 1) + 2;
                assert!(part < 1 << (margin_bits(w, kind) - 2), "W = {w}: {part}");
            };
            let (wt, edge) = (wide(w), 2 * w + 2);
            fits(w, wt, DET, w + wt + 1);
            fits(w, w, N_U, edge);
            fits(wt, wt, N_T, offset_bits(w) + 1);
        }
    }

    #[test]
    fn zero_origins_and_non_finite_inputs() {
        // A camera at the origin has a zero moment and a zero orig: stored, not forwarded.
        let q = query(
            [0.0; 3],
            [0.0, 0.0, -1.0],
            [-1.0, -1.0, -5.0],
            [1.0, -1.0, -5.0],
            [0.0, 1.0, -5.0],
        );
        let (ops, _) = datapath(&q, 18).unwrap();
        assert_eq!(ops.moment.m, [0; 3]);
        assert!(decide_inputs(&q, 18, 1.0).is_some());
        let bad = MtQuery {
            dir: [f32::NAN, 0.0, 1.0],
            ..q
        };
        assert!(datapath(&bad, 18).is_none());
    }
}
