//! Wyman & Nichols 2009, "Adaptive caustic maps using deferred shading": deferred refraction
//! (Sec. 3.1) and its multi-layer form (Sec. 3.1.1) for the eye view, deferred caustic maps (the
//! dense photon buffer by deferred shading, through several refractors: [`deferred_photons`],
//! Sec. 3.1.1, 3.2, Fig. 10 and 13), and adaptive caustic maps
//! (technique `adaptive`, Sec. 3.2-4.2): light-space geometry buffers ([`geometry_buffers`])
//! from which the photons of a virtual photon hierarchy are created by deferred shading while
//! it is traversed ([`adaptive`]).

pub mod adaptive;
pub mod deferred_photons;
pub mod deferred_refraction;
pub mod geometry_buffers;
pub mod push;
pub mod refractor_layers;
pub mod settings;

pub use adaptive::AdaptiveCaustics;
pub use deferred_photons::DeferredPhotons;
pub use deferred_refraction::DeferredRefraction;
pub use geometry_buffers::LightGeometryBuffers;
pub use settings::{Metric, PhotonRefraction, Refraction};
