//! The alias table (to be written).

/// Probability proportional to a weight, O(1) per sample (to be written).
#[derive(Clone, Copy, Debug)]
pub struct AliasTable<'a> {
    #[allow(dead_code)] // read by the sampling methods still to be written
    storage: &'a [u32],
}
