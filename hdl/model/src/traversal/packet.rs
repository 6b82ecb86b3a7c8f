//! The traversal unit's stream packets: a ray in, an answer out, as 32-bit words (word k at
//! bits `32k .. 32k + 32` of the stream's `tdata`). The one definition the RTL slices its
//! ports by and the drivers write and read (docs/traversal-unit.md, "Streams").

use sw_renderer::hit::Hit;

use super::UnitRay;

/// Words of a ray: origin, direction, t_max, t_min (fp32), flags, excluded triangle, id.
pub const RAY_WORDS: usize = 11;
/// Word indices of a ray packet.
pub mod ray_word {
    /// Origin x, y, z (three words).
    pub const ORIG: usize = 0;
    /// Direction x, y, z (three words).
    pub const DIR: usize = 3;
    pub const T_MAX: usize = 6;
    pub const T_MIN: usize = 7;
    /// Bit [`super::ANY_HIT`]: any-hit (shadow) ray; bit [`super::HAS_EXCLUDE`]: word
    /// [`EXCLUDE`] names a triangle that never counts.
    pub const FLAGS: usize = 8;
    /// The excluded triangle's global index.
    pub const EXCLUDE: usize = 9;
    pub const ID: usize = 10;
}
/// Flag bits of [`ray_word::FLAGS`].
pub const ANY_HIT: u32 = 1 << 0;
pub const HAS_EXCLUDE: u32 = 1 << 1;

/// Words of an answer: ray id, flags (bit 0: hit), global triangle index, t, u, v (fp32);
/// a miss has zeros beyond its flags.
pub const HIT_WORDS: usize = 6;
/// Word indices of an answer packet.
pub mod hit_word {
    pub const ID: usize = 0;
    /// Bit 0: the ray hit.
    pub const FLAGS: usize = 1;
    pub const TRIANGLE: usize = 2;
    pub const T: usize = 3;
    pub const U: usize = 4;
    pub const V: usize = 5;
}

impl UnitRay {
    /// The ray as its packet.
    pub fn to_words(&self) -> [u32; RAY_WORDS] {
        use ray_word::*;
        let mut w = [0u32; RAY_WORDS];
        for k in 0..3 {
            w[ORIG + k] = self.orig[k].to_bits();
            w[DIR + k] = self.dir[k].to_bits();
        }
        w[T_MAX] = self.t_max.to_bits();
        w[T_MIN] = self.t_min.to_bits();
        w[FLAGS] = if self.any_hit { ANY_HIT } else { 0 }
            | if self.exclude.is_some() {
                HAS_EXCLUDE
            } else {
                0
            };
        w[EXCLUDE] = self.exclude.unwrap_or(0);
        w[ID] = self.id;
        w
    }

    /// The ray a packet holds (flag bits other than the two defined are ignored).
    pub fn from_words(w: &[u32; RAY_WORDS]) -> UnitRay {
        use ray_word::*;
        let f = |k: usize| f32::from_bits(w[k]);
        UnitRay {
            orig: [f(ORIG), f(ORIG + 1), f(ORIG + 2)],
            dir: [f(DIR), f(DIR + 1), f(DIR + 2)],
            t_max: f(T_MAX),
            t_min: f(T_MIN),
            exclude: (w[FLAGS] & HAS_EXCLUDE != 0).then_some(w[EXCLUDE]),
            any_hit: w[FLAGS] & ANY_HIT != 0,
            id: w[ID],
        }
    }
}

/// The answer packet of ray `id`.
pub fn hit_to_words(id: u32, hit: Option<Hit>) -> [u32; HIT_WORDS] {
    use hit_word::*;
    let mut w = [0u32; HIT_WORDS];
    w[ID] = id;
    if let Some(h) = hit {
        w[FLAGS] = 1;
        w[TRIANGLE] = h.triangle;
        w[T] = h.t.to_bits();
        w[U] = h.u.to_bits();
        w[V] = h.v.to_bits();
    }
    w
}

/// The ray id and answer of a packet.
pub fn hit_from_words(w: &[u32; HIT_WORDS]) -> (u32, Option<Hit>) {
    use hit_word::*;
    let hit = (w[FLAGS] & 1 != 0).then(|| Hit {
        triangle: w[TRIANGLE],
        t: f32::from_bits(w[T]),
        u: f32::from_bits(w[U]),
        v: f32::from_bits(w[V]),
    });
    (w[ID], hit)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn packets_round_trip_bit_for_bit() {
        let ray = UnitRay {
            orig: [1.5, -0.0, f32::NAN],
            dir: [f32::INFINITY, 2.0, -3.25],
            t_max: f32::MAX,
            t_min: 1e-4,
            exclude: Some(0xAB_CDEF),
            any_hit: true,
            id: 77,
        };
        let back = UnitRay::from_words(&ray.to_words());
        assert_eq!(back.to_words(), ray.to_words());
        assert_eq!(
            (back.exclude, back.any_hit, back.id),
            (ray.exclude, true, 77)
        );
        let plain = UnitRay {
            exclude: None,
            any_hit: false,
            ..ray
        };
        assert_eq!(plain.to_words()[ray_word::FLAGS], 0);
        assert_eq!(UnitRay::from_words(&plain.to_words()).exclude, None);
        let hit = Hit {
            triangle: 9,
            t: 2.5,
            u: 0.25,
            v: -0.0,
        };
        let (id, back) = hit_from_words(&hit_to_words(5, Some(hit)));
        assert_eq!(
            (id, back.map(|h| (h.triangle, h.t, h.u, h.v.to_bits()))),
            (5, Some((9, 2.5, 0.25, (-0.0f32).to_bits())))
        );
        assert_eq!(hit_to_words(3, None), [3, 0, 0, 0, 0, 0]);
        assert_eq!(hit_from_words(&hit_to_words(3, None)), (3, None));
    }
}
