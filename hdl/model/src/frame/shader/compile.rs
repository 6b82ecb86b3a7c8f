//! The shading compiler: a scene's [`FrameConstants`] → the shader core's [`Program`], bit
//! for bit [`crate::frame::shade`]'s arithmetic, operation by operation in its order.
//!
//! One program per kind of material the scene uses (Phong: one per distinct exponent, its
//! square-and-multiply unrolled as [`Fp32::powi`] does it) and one for a miss; the lights are
//! unrolled. Material values are read with `MatConst`, so one program serves every material
//! of its kind. The constant memory holds, in order:
//! - per material (object) m, at `m · MATERIAL_STRIDE`: Phong (albedo), (Kd, Ks, 0); glass
//!   (ior, 1, ior) and (1, ior, 1/ior), the Fresnel (etai, etat, eta) of a ray inside and of
//!   one outside (their z lanes are also the refraction's eta); nothing for the others;
//! - the globals ([`Global`]);
//! - per light: distant (direction, intensity, fl(intensity·0.9)); point (position,
//!   intensity/4π). fl(I·0.9) is folded on the host because the shading computes
//!   fl(fl(I·0.9)·cos) with a loaded I: the same bits.
//!
//! A ray's spawned reflection and refraction rays past the maximum depth ([`PAST_DEPTH`])
//! are not pushed: their weight⊙background contribution is added to the settle sum and
//! counted (`PastDepth`). A shadow ray whose contribution is zero is not pushed
//! (`ZeroShadow`); glass counts `TotalInternal` when kr < 1 is false. Subtraction a − b is
//! `Add` of a and −b (the operator's own definition, `FloatFormat::sub`).

use sw_renderer::scene::MaterialKind;
use sw_renderer::shade::{DIFFUSE_PATTERN, MIRROR_WEIGHT};
use thiserror::Error;

use super::interpret::Program;
use super::isa::{
    input, Counter, Field, Instr, IsaError, Loc, Op, Pred, PushKind, Src, Word3, CODE, CONSTANTS,
    MATERIAL_STRIDE, PAST_DEPTH, REGISTERS,
};
use crate::fp32::{Fp32, Vec3};
use crate::frame::constants::{FrameConstants, LightConstants};

/// A scene the shader core cannot hold.
#[derive(Clone, Debug, PartialEq, Eq, Error)]
pub enum CompileError {
    #[error("the shading programs take {used} instructions; the shader core's program memory holds {limit}")]
    Code { used: usize, limit: usize },
    #[error("the shading constants take {used} entries; the shader core's constant memory holds {limit}")]
    Constants { used: usize, limit: usize },
    #[error("the {program} program needs {used} registers; the shader core has {limit}")]
    Registers {
        program: String,
        used: usize,
        limit: usize,
    },
    #[error("the {program} program: {source}")]
    Instruction { program: String, source: IsaError },
}

/// What a program shades: a miss or a material kind. Phong has one program per exponent.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ProgramKind {
    Miss,
    Diffuse,
    Phong,
    Mirror,
    Glass,
}

impl ProgramKind {
    pub const ALL: [ProgramKind; 5] = [
        ProgramKind::Miss,
        ProgramKind::Diffuse,
        ProgramKind::Phong,
        ProgramKind::Mirror,
        ProgramKind::Glass,
    ];

    pub fn of(kind: MaterialKind) -> ProgramKind {
        match kind {
            MaterialKind::Diffuse => ProgramKind::Diffuse,
            MaterialKind::Phong => ProgramKind::Phong,
            MaterialKind::Reflection => ProgramKind::Mirror,
            MaterialKind::ReflectionRefraction => ProgramKind::Glass,
        }
    }

    /// Index in [`ProgramKind::ALL`].
    pub fn index(self) -> usize {
        self as usize
    }

    pub fn name(self) -> &'static str {
        match self {
            ProgramKind::Miss => "miss",
            ProgramKind::Diffuse => "diffuse",
            ProgramKind::Phong => "phong",
            ProgramKind::Mirror => "mirror",
            ProgramKind::Glass => "glass",
        }
    }
}

/// The global constant entries, after the materials' (each a [`Word3`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Global {
    /// (0, 1, 2)
    Numbers,
    /// (0.5, 255, 0.8): Fresnel's half, a contribution's steps, the mirror's weight.
    Factors,
    /// (bias, 0.9, `Fp32::MAX`): the bias, the diffuse pattern, a distant light's distance.
    Shadow,
    Background,
}

const GLOBALS: usize = 4;

/// A light's intensity at P: loaded (distant), or computed in a register (point).
enum Intensity {
    Distant,
    Point(u8),
}

#[derive(Clone, Copy)]
enum LightKind {
    Distant,
    Point,
}

/// Where the constants are.
struct Layout {
    globals: usize,
    kinds: Vec<LightKind>,
    /// Each light's first entry.
    lights: Vec<usize>,
    size: usize,
}

impl Layout {
    fn new(c: &FrameConstants) -> Layout {
        let globals = c.materials.len() * MATERIAL_STRIDE;
        let mut next = globals + GLOBALS;
        let lights = (c.lights.iter())
            .map(|l| {
                let at = next;
                next += match l {
                    LightConstants::Distant { .. } => 3,
                    LightConstants::Point { .. } => 2,
                };
                at
            })
            .collect();
        let kinds = (c.lights.iter())
            .map(|l| match l {
                LightConstants::Distant { .. } => LightKind::Distant,
                LightConstants::Point { .. } => LightKind::Point,
            })
            .collect();
        Layout {
            globals,
            kinds,
            lights,
            size: next,
        }
    }

    fn entry(&self, g: Global) -> Src {
        Src::of(Loc::Const((self.globals + g as usize) as u16))
    }

    /// Lane `lane` of a global in every lane.
    fn global(&self, g: Global, lane: u8) -> Src {
        Src::broadcast(Loc::Const((self.globals + g as usize) as u16), lane)
    }

    fn zero(&self) -> Src {
        self.global(Global::Numbers, 0)
    }

    fn one(&self) -> Src {
        self.global(Global::Numbers, 1)
    }

    fn light(&self, k: usize, entry: usize) -> Src {
        Src::of(Loc::Const((self.lights[k] + entry) as u16))
    }
}

fn words(v: Vec3) -> Word3 {
    v.components().map(Fp32::bits)
}

fn constants(c: &FrameConstants, layout: &Layout) -> Vec<Word3> {
    let mut k = vec![[0; 3]; layout.size];
    let one = Fp32::ONE;
    for (m, mat) in c.materials.iter().enumerate() {
        let at = m * MATERIAL_STRIDE;
        match mat.kind {
            MaterialKind::Phong => {
                k[at] = words(mat.albedo);
                k[at + 1] = words(Vec3::new(mat.kd, mat.ks, Fp32::ZERO));
            }
            MaterialKind::ReflectionRefraction => {
                k[at] = words(Vec3::new(mat.ior, one, mat.ior));
                k[at + 1] = words(Vec3::new(one, mat.ior, mat.inv_ior));
            }
            MaterialKind::Diffuse | MaterialKind::Reflection => {}
        }
    }
    let g = |x: Global| layout.globals + x as usize;
    let pattern = Fp32::new(DIFFUSE_PATTERN);
    k[g(Global::Numbers)] = words(Vec3::of([0.0, 1.0, 2.0]));
    k[g(Global::Factors)] = words(Vec3::of([0.5, 255.0, MIRROR_WEIGHT]));
    k[g(Global::Shadow)] = words(Vec3::new(c.bias, pattern, Fp32::MAX));
    k[g(Global::Background)] = words(c.background);
    for (light, &at) in c.lights.iter().zip(&layout.lights) {
        match *light {
            LightConstants::Distant { dir, intensity } => {
                k[at] = words(dir);
                k[at + 1] = words(intensity);
                k[at + 2] = words(intensity.scale(pattern));
            }
            LightConstants::Point {
                pos,
                intensity_over_4pi,
            } => {
                k[at] = words(pos);
                k[at + 1] = words(intensity_over_4pi);
            }
        }
    }
    k
}

/// Operand shorthands.
fn reg(r: u8) -> Src {
    Src::reg(r)
}

/// Lane `lane` of register r in every lane.
fn lane(r: u8, lane: u8) -> Src {
    Src::broadcast(Loc::Reg(r), lane)
}

fn x(r: u8) -> Src {
    lane(r, 0)
}

fn mat(k: u8) -> Src {
    Src::of(Loc::MatConst(k))
}

fn mat_lane(k: u8, lane: u8) -> Src {
    Src::broadcast(Loc::MatConst(k), lane)
}

/// Predicates the programs write (p0 is always true, p1 is [`PAST_DEPTH`]): normalise's
/// n > 0; a shadow ray's contribution not zero; glass: cosi > 0 (Fresnel's), sint ≥ 1 then
/// the refraction pushed (kr < 1, not past the depth), c < 0, kr < 1, k < 0 then the
/// refraction past the depth.
const P_SCRATCH: u8 = 2;
const P_SHADOW: u8 = 3;
const P_INSIDE: u8 = 3;
const P_TIR: u8 = 4;
const P_REFRACT: u8 = 4;
const P_OUTSIDE: u8 = 5;
const P_KR: u8 = 6;
const P_K: u8 = 7;
const P_REFRACT_PAST: u8 = 7;

/// One program being written: straight-line code and its registers (a set bit of `used`
/// per register in use; r0..r6 are the thread's inputs).
struct Builder<'a> {
    layout: &'a Layout,
    code: Vec<Instr>,
    used: u64,
    /// Registers needed: one past the highest used.
    peak: usize,
}

impl Builder<'_> {
    /// The lowest free register. Registers past the machine's are refused (with the count)
    /// before encoding.
    fn reg(&mut self) -> u8 {
        let r = self.used.trailing_ones() as usize;
        self.used |= 1 << r;
        self.peak = self.peak.max(r + 1);
        r as u8
    }

    fn release(&mut self, r: u8) {
        self.used &= !(1 << r);
    }

    fn op(&mut self, op: Op) {
        self.code.push(Instr::new(op));
    }

    fn op_when(&mut self, pred: Pred, op: Op) {
        self.code.push(Instr::new(op).when(pred));
    }

    fn add(&mut self, d: u8, a: Src, b: Src) {
        self.op(Op::Add { d, a, b });
    }

    fn mul(&mut self, d: u8, a: Src, b: Src) {
        self.op(Op::Mul { d, a, b });
    }

    /// `Vec3::dot`: (a.x·b.x + a.y·b.y) + a.z·b.z, in every lane of a new register.
    fn dot(&mut self, a: Src, b: Src) -> u8 {
        let (p, s) = (self.reg(), self.reg());
        self.mul(p, a, b);
        self.add(s, lane(p, 0), lane(p, 1));
        self.add(s, reg(s), lane(p, 2));
        self.release(p);
        s
    }

    /// `Vec3::normalized` of register v, in place.
    fn normalise(&mut self, v: u8) {
        let n = self.dot(reg(v), reg(v));
        self.op(Op::Lt {
            p: P_SCRATCH,
            a: self.layout.zero(),
            b: x(n),
        });
        self.op(Op::Sqrt { d: n, a: x(n) });
        self.op(Op::Recip { d: n, a: x(n) });
        self.op_when(
            Pred::when(P_SCRATCH),
            Op::Mul {
                d: v,
                a: reg(v),
                b: x(n),
            },
        );
        self.release(n);
    }

    /// `Vec3::reflect_with`: i − n·(2·i_dot_n), in a new register.
    fn reflect(&mut self, i: Src, n: u8, i_dot_n: u8) -> u8 {
        let r = self.reg();
        self.mul(r, self.layout.global(Global::Numbers, 2), x(i_dot_n));
        self.mul(r, reg(n), x(r));
        self.add(r, i, reg(r).negated());
        r
    }

    /// `Contribution::of(weight ⊙ colour)`: fl(255·(w⊙c)) per lane, fixed, in a new register.
    fn contribution(&mut self, weight: Src, colour: Src) -> u8 {
        let c = self.reg();
        self.mul(c, weight, colour);
        self.mul(c, self.layout.global(Global::Factors, 1), reg(c));
        self.op(Op::Fix { d: c, a: reg(c) });
        c
    }

    /// The hit: P, N (normalised) and B = N·bias, in new registers.
    fn surface(&mut self) -> (u8, u8, u8) {
        let [o, d, t, n0] = [input::ORIGIN, input::DIRECTION, input::TUV, input::NORMALS];
        let (p, w, n, s) = (self.reg(), self.reg(), self.reg(), self.reg());
        self.mul(p, reg(d), lane(t, 0));
        self.add(p, reg(o), reg(p));
        self.add(w, self.layout.one(), lane(t, 1).negated());
        self.add(w, reg(w), lane(t, 2).negated());
        self.mul(n, reg(n0), x(w));
        self.mul(s, reg(n0 + 1), lane(t, 1));
        self.add(n, reg(n), reg(s));
        self.mul(s, reg(n0 + 2), lane(t, 2));
        self.add(n, reg(n), reg(s));
        self.release(s);
        self.normalise(n);
        let b = w; // w is no longer read: reused
        self.mul(b, reg(n), self.layout.global(Global::Shadow, 0));
        (p, n, b)
    }

    /// A spawned cast ray of `kind` along `dir` (normalised here) with `weight`, its origin
    /// already in the output record: pushed under one predicate; under the other (past the
    /// depth) its weight⊙background added to `sum` and counted. `preds` names them (push,
    /// past); by default they are not past the depth and past it.
    fn cast(&mut self, kind: PushKind, dir: u8, weight: u8, sum: u8, preds: Option<(u8, u8)>) {
        let (push, past) = match preds {
            Some((p, q)) => (Pred::when(p), Pred::when(q)),
            None => (Pred::unless(PAST_DEPTH), Pred::when(PAST_DEPTH)),
        };
        self.normalise(dir);
        self.op(Op::Out {
            f: Field::Direction,
            a: reg(dir),
        });
        self.op(Op::Out {
            f: Field::Payload,
            a: reg(weight),
        });
        self.op_when(push, Op::Push { kind });
        let c = self.contribution(reg(weight), self.layout.entry(Global::Background));
        self.op_when(
            past,
            Op::IAdd {
                d: sum,
                a: reg(sum),
                b: reg(c),
            },
        );
        self.op_when(
            past,
            Op::Count {
                counter: Counter::PastDepth,
            },
        );
        self.release(c);
    }

    fn end(&mut self, a: Src) {
        self.op(Op::End { a });
    }

    fn miss(&mut self) {
        let c = self.contribution(reg(input::WEIGHT), self.layout.entry(Global::Background));
        self.end(reg(c));
    }

    fn mirror(&mut self) {
        let (p, n, b) = self.surface();
        let d = input::DIRECTION;
        let c = self.dot(reg(d), reg(n));
        let r = self.reflect(reg(d), n, c);
        let w = self.reg();
        self.mul(
            w,
            reg(input::WEIGHT),
            self.layout.global(Global::Factors, 2),
        );
        self.add(p, reg(p), reg(b));
        self.op(Op::Out {
            f: Field::Origin,
            a: reg(p),
        });
        let sum = self.reg();
        self.op(Op::Mov {
            d: sum,
            a: self.layout.zero(),
        });
        self.cast(PushKind::Reflection, r, w, sum, None);
        self.end(reg(sum));
    }

    /// Diffuse (`exponent` None) or Phong: a shadow ray per light.
    fn lit(&mut self, exponent: Option<u32>) {
        let l = self.layout;
        let zero = l.zero();
        let (p, n, b) = self.surface();
        self.add(b, reg(p), reg(b));
        self.op(Op::Out {
            f: Field::Origin,
            a: reg(b),
        });
        let lights = l.lights.len();
        for k in 0..lights {
            let scope = self.used;
            let (dir, intensity, distance) = self.illuminate(k, p);
            let cos = self.dot(reg(n), dir.negated());
            self.op(Op::Max {
                d: cos,
                a: zero,
                b: x(cos),
            });
            let term = self.reg();
            match exponent {
                None => match intensity {
                    // fl(I·0.9) loaded.
                    Intensity::Distant => self.mul(term, l.light(k, 2), x(cos)),
                    Intensity::Point(i) => {
                        self.mul(term, reg(i), l.global(Global::Shadow, 1));
                        self.mul(term, reg(term), x(cos));
                    }
                },
                Some(e) => {
                    let i = match intensity {
                        Intensity::Distant => l.light(k, 1),
                        Intensity::Point(i) => reg(i),
                    };
                    let ldn = self.dot(dir, reg(n));
                    let r = self.reflect(dir, n, ldn);
                    let spec = self.dot(reg(r), reg(input::DIRECTION).negated());
                    self.op(Op::Max {
                        d: spec,
                        a: zero,
                        b: x(spec),
                    });
                    let spec = self.powi(spec, e);
                    self.mul(term, mat(0), i);
                    self.mul(term, reg(term), x(cos));
                    self.mul(term, reg(term), mat_lane(1, 0));
                    let t2 = r; // no longer read: reused
                    self.mul(t2, i, spec);
                    self.mul(t2, reg(t2), mat_lane(1, 1));
                    self.add(term, reg(term), reg(t2));
                }
            }
            let c = self.contribution(reg(input::WEIGHT), reg(term));
            self.op(Op::Nz {
                p: P_SHADOW,
                a: reg(c),
            });
            self.op(Op::Out {
                f: Field::Direction,
                a: dir.negated(),
            });
            self.op(Op::Out {
                f: Field::TMax,
                a: distance,
            });
            self.op(Op::Out {
                f: Field::Payload,
                a: reg(c),
            });
            self.op_when(
                Pred::when(P_SHADOW),
                Op::Push {
                    kind: PushKind::Shadow,
                },
            );
            self.op_when(
                Pred::unless(P_SHADOW),
                Op::Count {
                    counter: Counter::ZeroShadow,
                },
            );
            self.used = scope;
        }
        self.end(zero);
    }

    /// Light k at P: the direction the light travels, its intensity and its distance.
    fn illuminate(&mut self, k: usize, p: u8) -> (Src, Intensity, Src) {
        let l = self.layout;
        match l.kinds[k] {
            LightKind::Distant => (
                l.light(k, 0),
                Intensity::Distant,
                l.global(Global::Shadow, 2),
            ),
            LightKind::Point => {
                let v = self.reg();
                self.add(v, reg(p), l.light(k, 0).negated());
                let r2 = self.dot(reg(v), reg(v));
                let distance = self.reg();
                self.op(Op::Sqrt {
                    d: distance,
                    a: x(r2),
                });
                let inv = self.reg();
                self.op(Op::Recip {
                    d: inv,
                    a: x(distance),
                });
                self.mul(v, reg(v), x(inv));
                self.op(Op::Recip { d: inv, a: x(r2) });
                self.mul(inv, l.light(k, 1), x(inv));
                (reg(v), Intensity::Point(inv), x(distance))
            }
        }
    }

    /// `Fp32::powi` of lane x of register `base`: square-and-multiply from the exponent's leading
    /// bit (r = x; per lower bit r = r·r, then r = r·x if it is set; x^0 = 1).
    fn powi(&mut self, base: u8, n: u32) -> Src {
        if n == 0 {
            return self.layout.one();
        }
        // r is x until the first square writes a register.
        let mut r = base;
        for bit in (0..31 - n.leading_zeros()).rev() {
            let d = if r == base { self.reg() } else { r };
            self.mul(d, x(r), x(r));
            r = d;
            if n >> bit & 1 == 1 {
                self.mul(r, x(r), x(base));
            }
        }
        x(r)
    }

    fn glass(&mut self) {
        let l = self.layout;
        let (one, zero) = (l.one(), l.zero());
        let (p, n, b) = self.surface();
        let d = input::DIRECTION;
        let c = self.dot(reg(d), reg(n));
        // Fresnel.
        let cosi = self.reg();
        self.op(Op::Min {
            d: cosi,
            a: one,
            b: x(c),
        });
        self.op(Op::Max {
            d: cosi,
            a: one.negated(),
            b: x(cosi),
        });
        self.op(Op::Lt {
            p: P_INSIDE,
            a: zero,
            b: x(cosi),
        });
        let eta = self.reg(); // (etai, etat, eta)
        self.op(Op::Mov { d: eta, a: mat(1) });
        self.op_when(Pred::when(P_INSIDE), Op::Mov { d: eta, a: mat(0) });
        let q = self.reg(); // 1 − cosi·cosi
        self.mul(q, x(cosi), x(cosi));
        self.add(q, one, x(q).negated());
        let sint = self.reg();
        self.op(Op::Max {
            d: sint,
            a: zero,
            b: x(q),
        });
        self.op(Op::Sqrt {
            d: sint,
            a: x(sint),
        });
        self.mul(sint, lane(eta, 2), x(sint));
        self.op(Op::Le {
            p: P_TIR,
            a: one,
            b: x(sint),
        });
        let cost = self.reg();
        self.mul(cost, x(sint), x(sint));
        self.add(cost, one, x(cost).negated());
        self.op(Op::Max {
            d: cost,
            a: zero,
            b: x(cost),
        });
        self.op(Op::Sqrt {
            d: cost,
            a: x(cost),
        });
        // (etat·a, etai·a) and (etai·cost, etat·cost), a = |cosi|.
        let (ea, ec) = (self.reg(), self.reg());
        let swap = Src {
            swizzle: [1, 0, 0],
            ..reg(eta)
        };
        self.mul(ea, swap, x(cosi).absolute());
        self.mul(ec, reg(eta), x(cost));
        let (num, den) = (self.reg(), self.reg());
        self.add(num, reg(ea), reg(ec).negated());
        self.add(den, reg(ea), reg(ec));
        let inv = ea; // no longer read: reused
        self.code
            .push(Instr::new(Op::Recip { d: inv, a: x(den) }).lanes(0b001));
        self.code.push(
            Instr::new(Op::Recip {
                d: inv,
                a: lane(den, 1),
            })
            .lanes(0b010),
        );
        let kr = num;
        self.mul(kr, reg(num), reg(inv)); // (rs, rp)
        self.mul(kr, reg(kr), reg(kr));
        self.add(kr, lane(kr, 0), lane(kr, 1));
        self.mul(kr, x(kr), l.global(Global::Factors, 0));
        self.op_when(Pred::when(P_TIR), Op::Mov { d: kr, a: one });
        self.op(Op::Lt {
            p: P_OUTSIDE,
            a: x(c),
            b: zero,
        });
        self.op(Op::Lt {
            p: P_KR,
            a: x(kr),
            b: one,
        });
        self.op_when(
            Pred::unless(P_KR),
            Op::Count {
                counter: Counter::TotalInternal,
            },
        );
        // Refraction: cosi < 0 exactly when c < 0 (clamping keeps the sign).
        let (ci, e) = (cost, den); // no longer read: reused
        self.op(Op::Mov { d: ci, a: x(cosi) });
        self.op_when(
            Pred::when(P_OUTSIDE),
            Op::Mov {
                d: ci,
                a: x(cosi).negated(),
            },
        );
        self.op(Op::Mov {
            d: e,
            a: mat_lane(0, 2),
        });
        self.op_when(
            Pred::when(P_OUTSIDE),
            Op::Mov {
                d: e,
                a: mat_lane(1, 2),
            },
        );
        let k = sint; // no longer read: reused
        self.mul(k, x(e), x(e));
        self.mul(k, x(k), x(q));
        self.add(k, one, x(k).negated());
        self.op(Op::Lt {
            p: P_K,
            a: x(k),
            b: zero,
        });
        let m = q; // no longer read: reused
        self.mul(m, x(e), x(ci));
        self.op(Op::Sqrt { d: k, a: x(k) });
        self.add(m, x(m), x(k).negated());
        let t = self.reg();
        self.mul(t, reg(d), x(e));
        let v = k;
        self.op_when(
            Pred::when(P_OUTSIDE),
            Op::Mul {
                d: v,
                a: reg(n),
                b: x(m),
            },
        );
        self.op_when(
            Pred::unless(P_OUTSIDE),
            Op::Mul {
                d: v,
                a: reg(n).negated(),
                b: x(m),
            },
        );
        self.add(t, reg(t), reg(v));
        self.op_when(Pred::when(P_K), Op::Mov { d: t, a: zero });
        // Weights: w·(1 − kr) and w·kr.
        let (wt, wr) = (ec, eta); // no longer read: reused
        self.add(wt, one, x(kr).negated());
        self.mul(wt, reg(input::WEIGHT), x(wt));
        self.mul(wr, reg(input::WEIGHT), x(kr));
        // kr < 1 and not past the depth (the refraction pushed); kr < 1 and past it.
        let sel = ci; // no longer read: reused
        self.op(Op::Mov { d: sel, a: x(kr) });
        self.op_when(Pred::when(PAST_DEPTH), Op::Mov { d: sel, a: one });
        self.op(Op::Lt {
            p: P_REFRACT,
            a: x(sel),
            b: one,
        });
        self.op(Op::Mov { d: sel, a: x(kr) });
        self.op_when(Pred::unless(PAST_DEPTH), Op::Mov { d: sel, a: one });
        self.op(Op::Lt {
            p: P_REFRACT_PAST,
            a: x(sel),
            b: one,
        });
        // Origins P + B and P − B.
        let pm = self.reg();
        self.add(pm, reg(p), reg(b).negated());
        self.add(p, reg(p), reg(b));
        let origin = |s: &mut Self, outside: u8, inside: u8| {
            s.op_when(
                Pred::when(P_OUTSIDE),
                Op::Out {
                    f: Field::Origin,
                    a: reg(outside),
                },
            );
            s.op_when(
                Pred::unless(P_OUTSIDE),
                Op::Out {
                    f: Field::Origin,
                    a: reg(inside),
                },
            );
        };
        let sum = self.reg();
        self.op(Op::Mov { d: sum, a: zero });
        origin(self, pm, p);
        self.cast(
            PushKind::Refraction,
            t,
            wt,
            sum,
            Some((P_REFRACT, P_REFRACT_PAST)),
        );
        let r = self.reflect(reg(d), n, c);
        origin(self, p, pm);
        self.cast(PushKind::Reflection, r, wr, sum, None);
        self.end(reg(sum));
    }
}

/// One program's code, its kind and name (for errors).
struct Part {
    name: String,
    code: Vec<Instr>,
}

fn part<'a>(
    layout: &'a Layout,
    name: String,
    write: impl FnOnce(&mut Builder<'a>),
) -> Result<Part, CompileError> {
    let mut b = Builder {
        layout,
        code: Vec::new(),
        used: (1 << (input::NORMALS + 3)) - 1,
        peak: 0,
    };
    write(&mut b);
    if b.peak > REGISTERS {
        return Err(CompileError::Registers {
            program: name,
            used: b.peak,
            limit: REGISTERS,
        });
    }
    Ok(Part { name, code: b.code })
}

/// The shading programs of a scene: code (every instruction encoded, so the program is
/// known to be loadable), constants and entry points; a scene that does not fit the shader
/// core is an error naming the sizes.
pub fn compile(c: &FrameConstants) -> Result<Program, CompileError> {
    let layout = Layout::new(c);
    if layout.size > CONSTANTS {
        return Err(CompileError::Constants {
            used: layout.size,
            limit: CONSTANTS,
        });
    }
    // The programs, each once: (what it shades, its code).
    let mut parts: Vec<(Option<(MaterialKind, u32)>, Part)> = Vec::new();
    parts.push((None, part(&layout, "miss".into(), Builder::miss)?));
    for m in &c.materials {
        let key = Some((m.kind, m.exponent));
        if parts.iter().any(|(k, _)| *k == key) {
            continue;
        }
        let p = match m.kind {
            MaterialKind::Diffuse => part(&layout, "diffuse".into(), |b| b.lit(None))?,
            MaterialKind::Phong => {
                part(&layout, format!("Phong (exponent {})", m.exponent), |b| {
                    b.lit(Some(m.exponent))
                })?
            }
            MaterialKind::Reflection => part(&layout, "mirror".into(), Builder::mirror)?,
            MaterialKind::ReflectionRefraction => part(&layout, "glass".into(), Builder::glass)?,
        };
        parts.push((key, p));
    }
    let used: usize = parts.iter().map(|(_, p)| p.code.len()).sum();
    if used > CODE {
        return Err(CompileError::Code { used, limit: CODE });
    }
    let mut code = Vec::with_capacity(used);
    let mut entries = Vec::with_capacity(parts.len());
    for (key, p) in parts {
        for instr in &p.code {
            instr.encode().map_err(|source| CompileError::Instruction {
                program: p.name.clone(),
                source,
            })?;
        }
        entries.push((key, code.len() as u16));
        code.extend(p.code);
    }
    let entry = |key| entries.iter().find(|(k, _)| *k == key).unwrap().1;
    Ok(Program {
        code,
        constants: constants(c, &layout),
        material_entry: (c.materials.iter())
            .map(|m| entry(Some((m.kind, m.exponent))))
            .collect(),
        miss_entry: entry(None),
    })
}
