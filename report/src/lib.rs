//! The error-versus-run-time report as a library: scenes with exact references, the samplers
//! and warps under test, the runs, the outputs. The `report` binary (`src/main.rs`) is its
//! command line; `tests/report.rs` checks the references, the estimators and a quick run.
#![allow(clippy::needless_range_loop)]

pub mod app;
pub mod area;
#[cfg(feature = "blue-noise")]
pub mod bluenoise;
#[cfg(feature = "envmap")]
pub mod env_split;
#[cfg(feature = "envmap")]
pub mod envscene;
#[cfg(feature = "lights")]
pub mod many_lights;
pub mod math;
#[cfg(feature = "envmap")]
pub mod orientation;
pub mod output;
pub mod path;
#[cfg(feature = "envmap")]
pub use pfm;
pub mod plots;
pub mod run;
pub mod samplers;
#[cfg(feature = "spherical")]
pub mod solid_angle;
#[cfg(feature = "envmap")]
pub mod sphere_ref;
pub mod strata;
#[cfg(feature = "envmap")]
pub mod strata_env;
