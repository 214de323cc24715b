//! Reflective caustics as Wyman & Davis 2006 compute them (Sec. 4): "we reflect about the
//! surface normal and perform a ray-plane intersection with a single background plane"
//! (`reflection = plane`, in `shaders_glsl/shared/trace.glsl`), beside the depth search through
//! the light's view of the receivers (`reflection = depth-search`, the default).

use crate::scene::{MaterialKind, Scene};

/// The height of the background plane: the receiver map's plane where the scene has one (or the
/// rectangle that stands for it, `Scene::caustic_frame`), else the lowest point of the diffuse
/// surfaces (the floor), else 0.
pub fn background_plane(scene: &Scene) -> f32 {
    if let Some(r) = scene.framing_rectangle() {
        return r.plane_y;
    }
    let lowest = scene
        .objects
        .iter()
        .filter(|o| matches!(scene.material_of(o).kind, MaterialKind::Diffuse { .. }))
        .map(|o| o.mesh.bounds().0.y)
        .fold(f32::INFINITY, f32::min);
    if lowest.is_finite() {
        lowest
    } else {
        0.0
    }
}
