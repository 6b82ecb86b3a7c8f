//! Query traces: the ray-triangle queries of a real render, recorded to a compact binary file
//! (format in docs/trace.md) and replayed into any intersector for benchmarks and equivalence.

use crate::cosim_error::CosimError;
use hdl::mt::{query_from_words, query_words};
use hdl::regmap::OPERAND_COUNT;
use hw_model::{MtQuery, MtResult};
use rayon::prelude::*;
use std::io::{Read, Write};
use std::path::Path;
use std::sync::Mutex;
use sw_renderer::intersect::Intersector;
use sw_renderer::rays::EngineError;

pub const MAGIC: [u8; 8] = *b"RTFTRACE";
/// 2: records carry t_min (version 1 had 15 values a query).
pub const VERSION: u32 = 2;
/// Bytes before the first record: magic, version, reserved flags, count.
pub const HEADER_BYTES: usize = 8 + 4 + 4 + 8;
/// Bytes of one record: the query's 16 little-endian f32 (`hdl::mt::query_words`).
pub const RECORD_BYTES: usize = OPERAND_COUNT * 4;

fn trace_error(path: &Path, message: impl Into<String>) -> CosimError {
    CosimError::Trace {
        path: path.to_path_buf(),
        message: message.into(),
    }
}

/// Writes `queries` to `path` as a version-2 trace.
pub fn write_trace(path: &Path, queries: &[MtQuery]) -> Result<(), CosimError> {
    let mut bytes = Vec::with_capacity(HEADER_BYTES + queries.len() * RECORD_BYTES);
    bytes.extend_from_slice(&MAGIC);
    bytes.extend_from_slice(&VERSION.to_le_bytes());
    bytes.extend_from_slice(&0u32.to_le_bytes());
    bytes.extend_from_slice(&(queries.len() as u64).to_le_bytes());
    for q in queries {
        for w in query_words(q) {
            bytes.extend_from_slice(&w.to_le_bytes());
        }
    }
    std::fs::File::create(path)
        .and_then(|mut f| f.write_all(&bytes))
        .map_err(|e| trace_error(path, format!("cannot write: {e}")))
}

/// Reads a trace written by [`write_trace`], checking its header and length.
pub fn read_trace(path: &Path) -> Result<Vec<MtQuery>, CosimError> {
    let mut bytes = Vec::new();
    std::fs::File::open(path)
        .and_then(|mut f| f.read_to_end(&mut bytes))
        .map_err(|e| trace_error(path, format!("cannot read: {e}")))?;
    if bytes.len() < HEADER_BYTES {
        return Err(trace_error(
            path,
            format!(
                "{} bytes: shorter than the {HEADER_BYTES}-byte header",
                bytes.len()
            ),
        ));
    }
    if bytes[..8] != MAGIC {
        return Err(trace_error(
            path,
            format!(
                "bytes 0–7 are {:?}, expected the magic \"RTFTRACE\"",
                &bytes[..8]
            ),
        ));
    }
    let word = |at: usize| u32::from_le_bytes(bytes[at..at + 4].try_into().expect("4 bytes"));
    if word(8) != VERSION {
        return Err(trace_error(
            path,
            format!(
                "version {} at byte 8, this program reads version {VERSION}",
                word(8)
            ),
        ));
    }
    if word(12) != 0 {
        return Err(trace_error(
            path,
            format!(
                "flags {:#x} at byte 12: no flags are defined, expected 0",
                word(12)
            ),
        ));
    }
    let count = u64::from_le_bytes(bytes[16..24].try_into().expect("8 bytes"));
    let body = bytes.len() - HEADER_BYTES;
    if body as u64 != count.saturating_mul(RECORD_BYTES as u64) {
        return Err(trace_error(
            path,
            format!("header says {count} queries ({} bytes), the file has {body} bytes after the header", count.saturating_mul(RECORD_BYTES as u64)),
        ));
    }
    Ok(bytes[HEADER_BYTES..]
        .chunks_exact(RECORD_BYTES)
        .map(|r| {
            query_from_words(&std::array::from_fn(|k| {
                u32::from_le_bytes(r[4 * k..4 * k + 4].try_into().expect("4 bytes"))
            }))
        })
        .collect())
}

/// An intersector that records every query it is asked, then answers with `inner`.
pub struct Recorder<'a> {
    inner: &'a dyn Intersector,
    queries: Mutex<Vec<MtQuery>>,
}

impl<'a> Recorder<'a> {
    pub fn new(inner: &'a dyn Intersector) -> Self {
        Recorder {
            inner,
            queries: Mutex::new(Vec::new()),
        }
    }

    /// The queries recorded so far (batches in the order they arrived).
    pub fn into_queries(self) -> Vec<MtQuery> {
        self.queries
            .into_inner()
            .unwrap_or_else(|poisoned| poisoned.into_inner())
    }
}

impl Intersector for Recorder<'_> {
    fn name(&self) -> String {
        format!("recording {}", self.inner.name())
    }

    fn intersect_batch(
        &self,
        queries: &[MtQuery],
        results: &mut [MtResult],
    ) -> Result<(), EngineError> {
        self.queries
            .lock()
            .unwrap_or_else(|poisoned| poisoned.into_inner())
            .extend_from_slice(queries);
        self.inner.intersect_batch(queries, results)
    }
}

/// Queries per batch when replaying (the size of a renderer tile's wavefront).
pub const REPLAY_BATCH: usize = 4096;

/// Answers `queries` with `isect` in batches of [`REPLAY_BATCH`], on rayon's threads;
/// `progress` is called with the number of queries of each finished batch.
pub fn replay(
    isect: &dyn Intersector,
    queries: &[MtQuery],
    progress: &(dyn Fn(usize) + Sync),
) -> Result<Vec<MtResult>, EngineError> {
    let mut results = vec![MtResult::default(); queries.len()];
    queries
        .par_chunks(REPLAY_BATCH)
        .zip(results.par_chunks_mut(REPLAY_BATCH))
        .try_for_each(|(q, r)| -> Result<(), EngineError> {
            isect.intersect_batch(q, r)?;
            progress(q.len());
            Ok(())
        })?;
    Ok(results)
}

/// Where two result lists first disagree.
#[derive(Clone, Debug, PartialEq)]
pub struct Difference {
    pub index: usize,
    /// "hit", "t", "u" or "v".
    pub field: &'static str,
    /// The field's values as text (hit as a bool, t/u/v as value and bits).
    pub a: String,
    pub b: String,
}

impl std::fmt::Display for Difference {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "query {}: {} = {} vs {}",
            self.index, self.field, self.a, self.b
        )
    }
}

/// The first query whose results differ in any bit, and the first differing field.
pub fn first_difference(a: &[MtResult], b: &[MtResult]) -> Option<Difference> {
    assert_eq!(a.len(), b.len(), "result lists of one trace");
    let (index, (x, y)) = a
        .iter()
        .zip(b)
        .enumerate()
        .find(|(_, (x, y))| !x.same_bits(y))?;
    let float = |v: f32| format!("{v:e} ({:#010x})", v.to_bits());
    let (field, a, b) = if x.hit != y.hit {
        ("hit", x.hit.to_string(), y.hit.to_string())
    } else if x.t.to_bits() != y.t.to_bits() {
        ("t", float(x.t), float(y.t))
    } else if x.u.to_bits() != y.u.to_bits() {
        ("u", float(x.u), float(y.u))
    } else {
        ("v", float(x.v), float(y.v))
    };
    Some(Difference { index, field, a, b })
}

#[cfg(test)]
mod tests {
    use super::*;
    use sw_renderer::intersect::F32Intersector;

    fn query(k: f32) -> MtQuery {
        MtQuery {
            orig: [k, 1.0, 2.0],
            dir: [0.0, -0.0, f32::NAN],
            v0: [3.0; 3],
            v1: [k; 3],
            v2: [f32::INFINITY, 1e-40, -k],
            t_min: -k,
        }
    }

    #[test]
    fn traces_round_trip_bit_for_bit() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("t.trace");
        let queries: Vec<MtQuery> = (0..100).map(|k| query(k as f32 * 0.37)).collect();
        write_trace(&path, &queries).unwrap();
        assert_eq!(
            std::fs::metadata(&path).unwrap().len() as usize,
            HEADER_BYTES + 100 * RECORD_BYTES
        );
        let back = read_trace(&path).unwrap();
        let bits = |q: &MtQuery| query_words(q).to_vec();
        assert_eq!(
            back.iter().map(bits).collect::<Vec<_>>(),
            queries.iter().map(bits).collect::<Vec<_>>()
        );
    }

    #[test]
    fn damaged_traces_are_refused_with_the_reason() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("t.trace");
        write_trace(&path, &[query(1.0), query(2.0)]).unwrap();
        let good = std::fs::read(&path).unwrap();
        let check = |bytes: &[u8], expect: &str| {
            std::fs::write(&path, bytes).unwrap();
            let e = read_trace(&path).unwrap_err().to_string();
            assert!(e.contains(expect) && e.contains("t.trace"), "{e}");
        };
        check(&good[..good.len() - 1], "header says 2 queries");
        check(&good[..10], "shorter than the 24-byte header");
        let mut bad = good.clone();
        bad[0] = b'X';
        check(&bad, "magic");
        let mut bad = good.clone();
        bad[8] = VERSION as u8 + 1;
        check(&bad, &format!("version {}", VERSION + 1));
        let mut bad = good;
        bad[12] = 1;
        check(&bad, "flags");
        let e = read_trace(&dir.path().join("missing"))
            .unwrap_err()
            .to_string();
        assert!(e.contains("cannot read"), "{e}");
    }

    #[test]
    fn recorder_keeps_every_query_and_answers_like_its_inner_engine() {
        let rec = Recorder::new(&F32Intersector);
        let queries: Vec<MtQuery> = (0..10).map(|k| query(k as f32)).collect();
        let mut got = vec![MtResult::default(); 10];
        rec.intersect_batch(&queries[..4], &mut got[..4]).unwrap();
        rec.intersect_batch(&queries[4..], &mut got[4..]).unwrap();
        let want = replay(&F32Intersector, &queries, &|_| {}).unwrap();
        assert!(first_difference(&got, &want).is_none());
        assert_eq!(rec.into_queries().len(), 10);
    }

    #[test]
    fn first_difference_names_the_query_and_field() {
        let a = vec![
            MtResult {
                hit: true,
                t: 1.0,
                u: 0.5,
                v: 0.25
            };
            5
        ];
        let mut b = a.clone();
        assert_eq!(first_difference(&a, &b), None);
        b[3].u = 0.5000001;
        b[4].hit = false;
        let d = first_difference(&a, &b).unwrap();
        assert_eq!((d.index, d.field), (3, "u"));
        assert!(
            d.to_string()
                .starts_with("query 3: u = 5e-1 (0x3f000000) vs"),
            "{d}"
        );
        b[3].u = 0.5;
        assert_eq!(first_difference(&a, &b).unwrap().field, "hit");
    }
}
