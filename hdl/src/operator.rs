//! The interface every number-format operator shares, so the MT pipeline and the test and
//! Verilator drivers can be written once over any format and operator.
//!
//! An operator is a block with `clock`, inputs `a` (and `b` for binary operators) and an
//! output `y`; it is built with `new(stages)` for `stages <= max_stages()` and its latency is
//! exactly `stages` clock cycles.

use rust_hdl::prelude::*;
use std::fmt;
use std::str::FromStr;

/// The operators every number format provides (the same set as `hw_model::Format`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Op {
    Add,
    Sub,
    Mul,
    Recip,
    Lt,
    FromF32,
    ToF32,
    /// The square root, float formats only (`hw_model` has no fixed-point one): a fixed-point
    /// format's `max_stages` of it is 0 and its `rtl` [`OperatorError::NotInFormat`].
    Sqrt,
}

impl Op {
    /// The operators every number format provides (the MT lane's).
    pub const ALL: [Op; 7] = [
        Op::Add,
        Op::Sub,
        Op::Mul,
        Op::Recip,
        Op::Lt,
        Op::FromF32,
        Op::ToF32,
    ];

    pub fn name(self) -> &'static str {
        match self {
            Op::Add => "add",
            Op::Sub => "sub",
            Op::Mul => "mul",
            Op::Recip => "recip",
            Op::Lt => "lt",
            Op::FromF32 => "from_f32",
            Op::ToF32 => "to_f32",
            Op::Sqrt => "sqrt",
        }
    }
}

impl fmt::Display for Op {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

#[derive(Debug, thiserror::Error, PartialEq, Eq)]
pub enum OperatorError {
    #[error(
        "unknown operator `{0}`; expected one of add, sub, mul, recip, lt, from_f32, to_f32, sqrt"
    )]
    UnknownOp(String),
    #[error("{format} has no {op}: a fixed-point format has no square root")]
    NotInFormat { format: String, op: Op },
    #[error("{format} {op}: {stages} pipeline stages requested, at most {max}")]
    TooManyStages {
        format: String,
        op: Op,
        stages: usize,
        max: usize,
    },
}

impl FromStr for Op {
    type Err = OperatorError;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Op::ALL
            .into_iter()
            .chain([Op::Sqrt])
            .find(|op| op.name() == s)
            .ok_or_else(|| OperatorError::UnknownOp(s.to_string()))
    }
}

pub trait Operator: Block + Sized {
    /// Bits of input `a`.
    const A_WIDTH: usize;
    /// Bits of input `b`, 0 for a unary operator (no `b` port).
    const B_WIDTH: usize;
    /// Bits of output `y` (1 for a comparison).
    const Y_WIDTH: usize;

    fn new(stages: usize) -> Self;
    fn max_stages() -> usize;
    fn clock(&mut self) -> &mut Signal<In, Clock>;
    /// Drive the inputs with raw bit patterns (`b` is ignored by unary operators).
    fn set_inputs(&mut self, a: u64, b: u64);
    /// The output as a raw bit pattern.
    fn output(&self) -> u64;
}

/// Implements [`Operator`]'s port plumbing for an operator struct with fields
/// `clock`, `a`, (`b`,) `y` whose `new`/`max_stages` are inherent functions.
#[macro_export]
macro_rules! impl_operator {
    (@common) => {
        fn new(stages: usize) -> Self { Self::new(stages) }
        fn max_stages() -> usize { Self::max_stages() }
        fn clock(&mut self) -> &mut rust_hdl::prelude::Signal<rust_hdl::prelude::In, rust_hdl::prelude::Clock> { &mut self.clock }
    };
    (unary $ty:ty, [$($g:tt)*], $a:expr, $y:expr, out = $out:ident) => {
        impl<$($g)*> $crate::operator::Operator for $ty {
            const A_WIDTH: usize = $a;
            const B_WIDTH: usize = 0;
            const Y_WIDTH: usize = $y;
            $crate::impl_operator!(@common);
            fn set_inputs(&mut self, a: u64, _b: u64) { self.a.next = a.into(); }
            fn output(&self) -> u64 { $crate::impl_operator!(@out $out, self) }
        }
    };
    (binary $ty:ty, [$($g:tt)*], $a:expr, $y:expr, out = $out:ident) => {
        impl<$($g)*> $crate::operator::Operator for $ty {
            const A_WIDTH: usize = $a;
            const B_WIDTH: usize = $a;
            const Y_WIDTH: usize = $y;
            $crate::impl_operator!(@common);
            fn set_inputs(&mut self, a: u64, b: u64) { self.a.next = a.into(); self.b.next = b.into(); }
            fn output(&self) -> u64 { $crate::impl_operator!(@out $out, self) }
        }
    };
    (@out bits, $s:ident) => { $s.y.val().to_u64() };
    (@out bit, $s:ident) => { $s.y.val() as u64 };
}

/// Runs `inputs` through a freshly built operator in rust-hdl's simulator, one pair per
/// clock cycle, and returns the outputs in input order (the pipeline is flushed by
/// repeating the last input `stages` more times).
pub fn simulate_operator<T: Operator>(stages: usize, inputs: &[(u64, u64)]) -> Vec<u64> {
    let mut uut = T::new(stages);
    uut.connect_all();
    let mut out = Vec::with_capacity(inputs.len());
    let last = inputs.last().copied().unwrap_or((0, 0));
    for cycle in 0..inputs.len() + stages {
        let (a, b) = inputs.get(cycle).copied().unwrap_or(last);
        uut.set_inputs(a, b);
        uut.clock().next = Clock { clk: false };
        assert!(simulate(&mut uut, 1000), "operator logic did not settle");
        if cycle >= stages {
            out.push(uut.output());
        }
        uut.clock().next = Clock { clk: true };
        assert!(simulate(&mut uut, 1000), "operator logic did not settle");
    }
    out
}
