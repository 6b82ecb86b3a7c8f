//! Dual precision (docs/precision.md, "Dual precision"): a block-floating-point *filter*
//! decides the Möller-Trumbore tests that are certainly misses; every other test goes to the
//! *fallback* format, whose answer is the answer. A test is a certain miss only if one of
//! the filter's compared values is beyond its threshold by more than a derived bound of
//! the filter's and the fallback's rounding errors ([`Filter::certain_miss`]), so every
//! hit, and every (hit, t, u, v) the renderer reads, is the fallback's bit for bit.
//!
//! Two filters, both built in rust-hdl (`hdl::dual`): the bfp filter ([`bfp`]) and the
//! Plücker filter with sign decisions ([`plucker`], [`signs`]).

use std::fmt;
use std::str::FromStr;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Arc;

use sw_renderer::intersect::{Intersector, MtQuery, MtResult};
use sw_renderer::rays::EngineError;
use thiserror::Error;

use crate::mt::mt_model;

pub mod bfp;
pub mod plucker;
pub mod signs;
use crate::{catalogue, lookup, Format, FormatError};

#[derive(Debug, Error, PartialEq, Eq)]
pub enum DualError {
    #[error("format pair `{0}`: expected FILTER/FALLBACK, such as bfp18/fp32")]
    Malformed(String),
    #[error("format pair `{pair}`: the {half} half: {source}")]
    Half {
        pair: String,
        half: &'static str,
        source: FormatError,
    },
    #[error(
        "format pair `{pair}`: the filter `{filter}` is not block floating point: a pair's filter is bfpW with W from {min} to {max}, as in bfp18/fp32"
    )]
    NotBfp {
        pair: String,
        filter: String,
        min: u32,
        max: u32,
    },
    #[error(
        "format pair `{pair}`: block floating point `{filter}` needs a mantissa width of {min} to {max} bits, as in bfp18"
    )]
    BfpWidth {
        pair: String,
        filter: String,
        min: u32,
        max: u32,
    },
    #[error(
        "format pair `{pair}`: a block-floating-point filter needs a float fallback that holds fp32 exactly (8 exponent and 23 fraction bits or more), not {fallback}"
    )]
    BfpFallback { pair: String, fallback: String },
}

/// A `bfpW` filter (block floating point with W-bit mantissas, [`bfp`]) and the fallback
/// whose answers it must reproduce.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct FormatPair {
    /// W, the filter's mantissa width (its exponent is shared by three components).
    pub filter_width: u32,
    pub fallback: Format,
}

impl FormatPair {
    /// `bfpW/FALLBACK`: W in [`bfp::WIDTHS`], the fallback anything [`lookup`] takes that
    /// holds fp32 exactly (the filter's margins assume the fallback rounds no more than
    /// fp32).
    pub fn parse(s: &str) -> Result<FormatPair, DualError> {
        let pair = s.trim().to_string();
        let halves: Vec<&str> = pair.split('/').map(str::trim).collect();
        let [filter, fallback] = halves[..] else {
            return Err(DualError::Malformed(pair));
        };
        if filter.is_empty() || fallback.is_empty() {
            return Err(DualError::Malformed(pair));
        }
        let (filter, fallback) = (filter.to_string(), fallback.to_string());
        let fallback = lookup(&fallback).map_err(|source| DualError::Half {
            pair: pair.clone(),
            half: "fallback",
            source,
        })?;
        let (min, max) = (*bfp::WIDTHS.start(), *bfp::WIDTHS.end());
        let Some(width) = filter
            .to_ascii_lowercase()
            .strip_prefix("bfp")
            .map(str::to_string)
        else {
            return Err(DualError::NotBfp {
                pair,
                filter,
                min,
                max,
            });
        };
        let filter_width = width
            .parse()
            .ok()
            .filter(|w| bfp::WIDTHS.contains(w))
            .ok_or_else(|| DualError::BfpWidth {
                pair: pair.clone(),
                filter: filter.clone(),
                min,
                max,
            })?;
        if !holds_fp32(&fallback) {
            return Err(DualError::BfpFallback {
                pair,
                fallback: label(&fallback),
            });
        }
        Ok(FormatPair {
            filter_width,
            fallback,
        })
    }
}

/// A catalogue name where there is one, else the generic spelling.
fn label(format: &Format) -> String {
    catalogue()
        .iter()
        .find(|n| n.format == *format)
        .map_or_else(|| format.to_string(), |n| n.name.to_string())
}

/// Whether converting fp32 into `format` is exact (a superset of fp32's normal numbers).
fn holds_fp32(format: &Format) -> bool {
    matches!(*format, Format::Float { exp, man } if exp >= 8 && man >= 23)
}

impl fmt::Display for FormatPair {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "bfp{}/{}", self.filter_width, label(&self.fallback))
    }
}

impl FromStr for FormatPair {
    type Err = DualError;
    fn from_str(s: &str) -> Result<Self, DualError> {
        FormatPair::parse(s)
    }
}

/// What a `--format` names: one format, or a filter/fallback pair.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FormatChoice {
    Single(Format),
    Pair(FormatPair),
}

#[derive(Debug, Error, PartialEq, Eq)]
pub enum ChoiceError {
    #[error(transparent)]
    Format(#[from] FormatError),
    #[error(transparent)]
    Pair(#[from] DualError),
}

impl FromStr for FormatChoice {
    type Err = ChoiceError;
    /// A `/` makes it a pair ([`FormatPair::parse`]), else [`lookup`].
    fn from_str(s: &str) -> Result<Self, ChoiceError> {
        Ok(if s.contains('/') {
            FormatChoice::Pair(FormatPair::parse(s)?)
        } else {
            FormatChoice::Single(lookup(s)?)
        })
    }
}

impl fmt::Display for FormatChoice {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            FormatChoice::Single(format) => f.write_str(&label(format)),
            FormatChoice::Pair(pair) => pair.fmt(f),
        }
    }
}

/// What the filter computes: the two filters hardware builds (`hdl::dual::slot_filter`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum FilterKind {
    /// Block floating point ([`bfp`]): the query translated in integers, W-bit blocks,
    /// integer products, margins from the bits actually dropped, decisions on short floats
    /// rounded outward. The engines' filter.
    #[default]
    Bfp,
    /// Plücker form ([`plucker`]): det and the numerators as dot products of per-ray and
    /// per-triangle blocks, no translation per test, margins from block exponents; decided
    /// by signs and bit lengths ([`signs::decide`]).
    Plucker,
}

impl FilterKind {
    pub const ALL: [FilterKind; 2] = [FilterKind::Bfp, FilterKind::Plucker];

    /// The CLI's names (`--dual-filter`).
    pub fn name(self) -> &'static str {
        match self {
            FilterKind::Bfp => "bfp",
            FilterKind::Plucker => "plucker-signs",
        }
    }
}

named_choice!(FilterKind, "dual-precision filter");

/// The filter: `pair.filter_width`'s blocks, moved exactly in integers ([`bfp`]) or held
/// per ray and per triangle ([`plucker`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Filter {
    pub pair: FormatPair,
    pub kind: FilterKind,
}

impl Filter {
    pub fn new(pair: FormatPair, kind: FilterKind) -> Filter {
        Filter { pair, kind }
    }

    /// Whether the fallback certainly answers "miss": one of its tests (|det| < eps,
    /// u < 0, u > 1, v < 0, u + v > 1, t ≤ t_min) is decided by the filter's value lying beyond
    /// the threshold by more than `margin_scale` × its margin (the filter's and the
    /// fallback's error bound). `margin_scale` is 1 for the derived bound; the tests shrink it
    /// to show that a smaller margin is wrong. Non-finite inputs and values out of the
    /// filter's range are never certain.
    pub fn certain_miss(&self, q: &MtQuery, margin_scale: f64) -> bool {
        self.decide(q, margin_scale).is_some()
    }

    /// The filter's result, as a miss, if the query is a certain miss.
    fn decide(&self, q: &MtQuery, margin_scale: f64) -> Option<MtResult> {
        let width = self.pair.filter_width;
        let miss = match self.kind {
            FilterKind::Bfp => bfp::certain_miss(q, width, margin_scale),
            FilterKind::Plucker => plucker::certain_miss(q, width, margin_scale),
        };
        miss.then_some(MtResult::default())
    }
}

/// Counts of a [`DualIntersector`]'s work.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct DualStats {
    pub tests: u64,
    /// Tests the filter decided alone.
    pub certain_misses: u64,
}

impl DualStats {
    /// Tests answered by the fallback.
    pub fn forwarded(&self) -> u64 {
        self.tests - self.certain_misses
    }

    /// forwarded / tests (0 without tests).
    pub fn forwarded_share(&self) -> f64 {
        self.forwarded() as f64 / self.tests.max(1) as f64
    }
}

#[derive(Debug, Default)]
struct Counters {
    tests: AtomicU64,
    certain_misses: AtomicU64,
}

/// The dual-precision model as an [`Intersector`]: a certain miss answers with the filter's
/// result (`hit` false; a miss's t, u, v mean nothing); every other query is
/// [`mt_model`] in the fallback format. Clones share their counters, so a caller
/// can keep one to read [`DualIntersector::stats`] after a render.
#[derive(Clone, Debug)]
pub struct DualIntersector {
    pub filter: Filter,
    counters: Arc<Counters>,
}

impl DualIntersector {
    /// `pair` with the engines' filter ([`FilterKind::default`], bfp).
    pub fn new(pair: FormatPair) -> DualIntersector {
        DualIntersector::with_filter(Filter::new(pair, FilterKind::default()))
    }

    pub fn with_filter(filter: Filter) -> DualIntersector {
        DualIntersector {
            filter,
            counters: Arc::default(),
        }
    }

    pub fn stats(&self) -> DualStats {
        DualStats {
            tests: self.counters.tests.load(Ordering::Relaxed),
            certain_misses: self.counters.certain_misses.load(Ordering::Relaxed),
        }
    }
}

impl Intersector for DualIntersector {
    /// "model bfp18/fp32".
    fn name(&self) -> String {
        format!("model {}", self.filter.pair)
    }

    fn intersect_batch(
        &self,
        queries: &[MtQuery],
        results: &mut [MtResult],
    ) -> Result<(), EngineError> {
        assert_eq!(queries.len(), results.len(), "one result slot per query");
        let mut misses = 0;
        for (q, r) in queries.iter().zip(results.iter_mut()) {
            *r = match self.filter.decide(q, 1.0) {
                Some(miss) => {
                    misses += 1;
                    miss
                }
                None => mt_model(&self.filter.pair.fallback, q),
            };
        }
        self.counters
            .tests
            .fetch_add(queries.len() as u64, Ordering::Relaxed);
        self.counters
            .certain_misses
            .fetch_add(misses, Ordering::Relaxed);
        Ok(())
    }
}
