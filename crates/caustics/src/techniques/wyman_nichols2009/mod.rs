//! Wyman & Nichols 2009, "Adaptive caustic maps using deferred shading": deferred refraction
//! (Sec. 3.1) and its multi-layer form (Sec. 3.1.1), for the eye view.

pub mod deferred_refraction;
pub mod settings;

pub use deferred_refraction::DeferredRefraction;
pub use settings::Refraction;
