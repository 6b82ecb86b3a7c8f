//! The bit-accurate model of the hardware arithmetic as an [`Intersector`]: no HDL, any format.

use sw_renderer::intersect::{Intersector, MtQuery, MtResult};
use sw_renderer::rays::EngineError;

use crate::mt::mt_model_scaled;
use crate::{catalogue, Advance, Edges, Format};

/// Answers every query with [`crate::mt_model_edges`] in `format` with the edge test `edges`,
/// on the query's ray started where `advance` says, scaled by 2^`scale_exp`
/// (`crate::precision::auto_scale_exp`; 0: unscaled). The port stays fp32.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ModelIntersector {
    pub format: Format,
    pub scale_exp: i32,
    pub edges: Edges,
    pub advance: Advance,
}

impl ModelIntersector {
    /// The unscaled model of `format` as the hardware lanes compute: exact edges, the ray
    /// from its origin.
    pub fn new(format: Format) -> ModelIntersector {
        ModelIntersector {
            format,
            scale_exp: 0,
            edges: Edges::Exact,
            advance: Advance::None,
        }
    }
}

impl Intersector for ModelIntersector {
    /// "model fp16" for catalogue formats, else the generic spelling ("model e6m9").
    fn name(&self) -> String {
        let label = catalogue()
            .iter()
            .find(|n| n.format == self.format)
            .map(|n| n.name.to_string());
        format!("model {}", label.unwrap_or_else(|| self.format.to_string()))
    }

    fn intersect_batch(
        &self,
        queries: &[MtQuery],
        results: &mut [MtResult],
    ) -> Result<(), EngineError> {
        assert_eq!(queries.len(), results.len(), "one result slot per query");
        for (q, r) in queries.iter().zip(results.iter_mut()) {
            *r = self.advance.run(q, |q| {
                mt_model_scaled(&self.format, self.scale_exp, self.edges, q)
            });
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::rngs::StdRng;
    use rand::{Rng, SeedableRng};
    use sw_renderer::intersect::F32Intersector;

    /// A value on the grid k·2^-bits, |value| ≤ max.
    fn grid(r: &mut StdRng, max: f32, bits: i32) -> f32 {
        let steps = (max * 2f32.powi(bits)) as i32;
        r.gen_range(-steps..=steps) as f32 * 2f32.powi(-bits)
    }

    /// Rays aimed near random triangles with every coordinate on a dyadic grid, so every
    /// nonzero intermediate of MT is far above fp32's subnormal range: the model must then
    /// equal the f32 reference bit for bit (NaN from a zero determinant matches any NaN).
    fn grid_query(r: &mut StdRng) -> MtQuery {
        let mut p = || [grid(r, 64.0, 8), grid(r, 64.0, 8), grid(r, 64.0, 8)];
        let (orig, v0, v1, v2) = (p(), p(), p(), p());
        let (a, b) = (grid(r, 1.0, 4).abs() - 0.125, grid(r, 1.0, 4).abs() - 0.125);
        // The hit is at t = 1: lower bounds on both sides of it, and exactly at it.
        let t_min = [0.0, 0.5, 1.0, 1.5][r.gen_range(0..4)];
        MtQuery::aimed(orig, [v0, v1, v2], (a, b), t_min)
    }

    #[test]
    fn fp32_model_equals_the_f32_reference() {
        let mut r = StdRng::seed_from_u64(31);
        let queries: Vec<MtQuery> = (0..50_000).map(|_| grid_query(&mut r)).collect();
        let mut want = vec![MtResult::default(); queries.len()];
        let mut got = want.clone();
        F32Intersector.intersect_batch(&queries, &mut want).unwrap();
        let model = ModelIntersector::new(crate::lookup("fp32").unwrap());
        model.intersect_batch(&queries, &mut got).unwrap();
        let same = |x: f32, y: f32| x.to_bits() == y.to_bits() || (x.is_nan() && y.is_nan());
        for ((q, g), w) in queries.iter().zip(&got).zip(&want) {
            assert!(
                g.hit == w.hit && same(g.t, w.t) && same(g.u, w.u) && same(g.v, w.v),
                "{q:?}: model {g:?}, f32 {w:?}"
            );
        }
        let hits = want.iter().filter(|w| w.hit).count();
        assert!(
            hits > 10_000,
            "only {hits} hits: the generator no longer aims at triangles"
        );
        assert_eq!(model.name(), "model fp32");
    }

    #[test]
    fn narrow_format_changes_results_and_names_itself() {
        let mut r = StdRng::seed_from_u64(32);
        let queries: Vec<MtQuery> = (0..1_000).map(|_| grid_query(&mut r)).collect();
        let mut fp32 = vec![MtResult::default(); queries.len()];
        let mut bf16 = fp32.clone();
        ModelIntersector::new(crate::lookup("fp32").unwrap())
            .intersect_batch(&queries, &mut fp32)
            .unwrap();
        let narrow = ModelIntersector::new(crate::lookup("bf16").unwrap());
        narrow.intersect_batch(&queries, &mut bf16).unwrap();
        assert!(fp32.iter().zip(&bf16).filter(|(a, b)| a.t != b.t).count() > 100);
        assert_eq!(narrow.name(), "model bf16");
        let custom = ModelIntersector::new(crate::lookup("e6m9").unwrap());
        assert_eq!(custom.name(), "model e6m9");
    }
}
