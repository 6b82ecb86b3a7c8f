//! The Plücker lane's operands as one word vector: what a Plücker slot
//! ([`super::slot::FilterSlot`]) takes beside the fp32 query, and how a driver packs
//! `hw_model::dual::plucker::Operands` (the ray's and the triangle's stored vectors, formed
//! once per ray and per scene). Each block is three component words (the mantissa's two's
//! complement, its low bits read) and its grid exponent's biased field
//! ([`EXP_BIAS`](super::align_add::EXP_BIAS)), in the order of [`BLOCKS`]; then ṽ0·ñ in two
//! words and its field, v0's cut and its field, and the stored flag (0: the test is
//! forwarded).

use hw_model::dual::plucker::{BlockBits, Operands};

use super::align_add::EXP_BIAS;

/// The blocks in their word order, four words each: dir, m, −orig, n, e1, −e2, e3,
/// v0 × e1, −(v0 × e2), v1 × e3.
pub const BLOCKS: usize = 10;
/// ṽ0·ñ's two words and field.
pub const OFFSET_WORD: usize = 4 * BLOCKS;
/// v0's cut: three words and a field.
pub const CUT_WORD: usize = OFFSET_WORD + 3;
/// 1 if the ray and the triangle have stored vectors.
pub const STORED_WORD: usize = CUT_WORD + 4;
pub const OPERAND_WORDS: usize = STORED_WORD + 1;
pub const OPERAND_BITS: usize = 32 * OPERAND_WORDS;

/// The words of `ops` (`None`: nothing stored, every other word 0).
pub fn operand_words(ops: Option<&Operands>) -> [u32; OPERAND_WORDS] {
    let mut words = [0; OPERAND_WORDS];
    let Some(o) = ops else {
        return words;
    };
    let field = |lsb: i32| (i64::from(lsb) + EXP_BIAS as i64) as u32;
    let mut put = |at: usize, b: &BlockBits<3>| {
        for k in 0..3 {
            words[at + k] = b.m[k] as u32;
        }
        words[at + 3] = field(b.lsb);
    };
    let blocks = [
        &o.dir,
        &o.moment,
        &o.orig,
        &o.n,
        &o.edges[0],
        &o.edges[1],
        &o.edges[2],
        &o.moments[0],
        &o.moments[1],
        &o.moments[2],
    ];
    for (i, b) in blocks.into_iter().enumerate() {
        put(4 * i, b);
    }
    put(CUT_WORD, &o.v0_cut);
    let offset = o.offset.m[0];
    words[OFFSET_WORD] = offset as u32;
    words[OFFSET_WORD + 1] = (offset >> 32) as u32;
    words[OFFSET_WORD + 2] = field(o.offset.lsb);
    words[STORED_WORD] = 1;
    words
}
