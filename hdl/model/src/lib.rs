//! Bit-accurate software model of the accelerator's arithmetic.
//!
//! A [`Format`] is either a float `(exp, man)` or a fixed-point `(int, frac)` format; values
//! travel as raw bit patterns in a `u64` (low `width()` bits). Every operator here is the
//! reference the rust-hdl operators and the Verilated hardware are checked against bit for
//! bit. No rust-hdl in this crate. It implements the renderer's seams (`sw_renderer::intersect`,
//! `sw_renderer::rays`): the model as an intersector ([`engine`]) and the traversal unit's
//! model ([`traversal`]); the renderer itself depends on no hardware crate.

/// A closed list of named choices (a CLI value, a config value), as [`named_choice!`] gives
/// it: what a command line parser lists and parses.
pub trait NamedChoice: Copy + Send + Sync + std::str::FromStr<Err = String> + 'static {
    /// Every choice, in the order a help text lists them.
    const CHOICES: &'static [Self];
    fn choice_name(self) -> &'static str;
}

/// `Display`, `FromStr` and [`NamedChoice`] of a closed list of named choices from its `ALL`
/// and `name()`: the parse error names `$what`, the bad value and the list.
macro_rules! named_choice {
    ($ty:ty, $what:literal) => {
        impl $crate::NamedChoice for $ty {
            const CHOICES: &'static [Self] = &<$ty>::ALL;
            fn choice_name(self) -> &'static str {
                self.name()
            }
        }

        impl std::fmt::Display for $ty {
            fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                f.write_str(self.name())
            }
        }

        impl std::str::FromStr for $ty {
            type Err = String;
            fn from_str(s: &str) -> Result<Self, String> {
                <$ty>::ALL
                    .into_iter()
                    .find(|c| c.name() == s)
                    .ok_or_else(|| {
                        let names: Vec<&str> = <$ty>::ALL.iter().map(|c| c.name()).collect();
                        format!(
                            concat!("unknown ", $what, " `{}`: expected {}"),
                            s,
                            names.join(" or ")
                        )
                    })
            }
        }
    };
}

pub mod advance;
pub mod catalogue;
pub mod dual;
pub mod edges;
pub mod engine;
mod fixed;
mod float;
pub mod format;
pub mod fp32;
pub mod frame;
pub mod mt;
pub mod precision;
pub mod traversal;

pub use advance::Advance;
pub use catalogue::{catalogue, lookup, HwFormat, NamedFormat};
pub use dual::{DualIntersector, FormatChoice, FormatPair};
pub use edges::Edges;
pub use engine::ModelIntersector;
pub use format::{Format, FormatError, Overflow, Quant};
pub use mt::{mt_model, mt_model_edges, mt_model_scaled, scale_query, MtQuery, MtResult};

#[cfg(test)]
mod tests {
    use super::*;
    use crate::precision::SpawnChoice;

    /// Every name parses back to its choice and displays as itself; `bad` is an error naming
    /// it and the `list`.
    fn names_round_trip<T: NamedChoice + PartialEq + std::fmt::Debug + std::fmt::Display>(
        bad: &str,
        list: &str,
    ) {
        for &c in T::CHOICES {
            assert_eq!(c.choice_name().parse::<T>(), Ok(c));
            assert_eq!(c.to_string(), c.choice_name());
        }
        let e = bad.parse::<T>().unwrap_err();
        assert!(e.contains(&format!("`{bad}`")) && e.contains(list), "{e}");
    }

    #[test]
    fn named_choices_parse_their_names_and_list_them_in_errors() {
        names_round_trip::<SpawnChoice>("format_aware", "thesis or format-aware");
        names_round_trip::<Edges>("loose", "exact or conservative");
        names_round_trip::<Advance>("far", "none or triangle-box or leaf-box");
    }
}
