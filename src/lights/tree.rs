//! The light tree (to be written).

/// A light's bounds for the tree's importance (to be written).
#[derive(Clone, Copy, Debug)]
pub struct LightBounds {
    /// Lower corner of the box around the emitter.
    pub min: [f32; 3],
    /// Upper corner of the box around the emitter.
    pub max: [f32; 3],
    /// Emitted power (>= 0).
    pub power: f32,
    /// Principal emission direction (unit).
    pub axis: [f32; 3],
    /// Cosine of the spread of normals around the axis.
    pub cos_theta_o: f32,
    /// Cosine of the emission falloff beyond `theta_o`.
    pub cos_theta_e: f32,
    /// Whether the emitter emits on both sides.
    pub two_sided: bool,
}

/// A bounding-volume tree over [`LightBounds`] (to be written).
#[derive(Clone, Copy, Debug)]
pub struct LightTree<'a> {
    #[allow(dead_code)] // read by the sampling methods still to be written
    storage: &'a [u32],
}
