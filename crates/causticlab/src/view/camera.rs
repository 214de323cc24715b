//! The viewer's camera and light controls: orbit about the camera's target (drag to turn, wheel
//! to move in and out) or fly (arrow keys and Page Up/Down move, drag to look), and dragging the first light
//! about the vertical axis through the scene's specular objects (Ctrl + drag; up and down moves
//! it higher and lower). Each writes the scene's camera or light; the renderer takes the new
//! pose at the next frame (`Renderer::set_pose`).

use caustics::scene::{Camera, LightKind, Scene};
use glam::{Mat3, Vec3};

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Mode {
    Orbit,
    Fly,
}

impl Mode {
    pub fn name(self) -> &'static str {
        match self {
            Mode::Orbit => "orbit",
            Mode::Fly => "fly",
        }
    }
}

/// Radians per pixel dragged.
const TURN: f32 = 0.006;
/// Pitch stays this far from straight up or down.
const PITCH_LIMIT: f32 = 1.5;

/// Yaw (about +y, 0 looking down -z) and pitch of the direction `d`.
fn angles(d: Vec3) -> (f32, f32) {
    let d = d.normalize_or_zero();
    (d.x.atan2(-d.z), d.y.clamp(-1.0, 1.0).asin())
}

fn direction(yaw: f32, pitch: f32) -> Vec3 {
    Vec3::new(yaw.sin() * pitch.cos(), pitch.sin(), -yaw.cos() * pitch.cos())
}

/// Turns `camera` by a drag of (dx, dy) pixels: about its target (orbit) or in place (fly).
pub fn drag(camera: &mut Camera, mode: Mode, dx: f32, dy: f32) {
    let view = camera.target - camera.eye;
    let dist = view.length().max(1e-4);
    let (yaw, pitch) = angles(view);
    let (yaw, pitch) = (yaw + dx * TURN, (pitch - dy * TURN).clamp(-PITCH_LIMIT, PITCH_LIMIT));
    let d = direction(yaw, pitch);
    match mode {
        Mode::Orbit => camera.eye = camera.target - d * dist,
        Mode::Fly => camera.target = camera.eye + d * dist,
    }
}

/// Moves the eye toward (positive `steps`) or away from the target, 10% a step.
pub fn dolly(camera: &mut Camera, steps: f32) {
    let view = camera.eye - camera.target;
    let scaled = view * 0.9f32.powf(steps);
    if scaled.length() > 1e-3 {
        camera.eye = camera.target + scaled;
    }
}

/// Flies eye and target by (right, up, forward) in units of a tenth of their distance.
pub fn fly(camera: &mut Camera, right: f32, up: f32, forward: f32) {
    let view = camera.target - camera.eye;
    let step = 0.1 * view.length().max(1e-3);
    let f = view.normalize_or_zero();
    let r = f.cross(Vec3::Y).normalize_or_zero();
    let delta = (r * right + Vec3::Y * up + f * forward) * step;
    camera.eye += delta;
    camera.target += delta;
}

/// Drags the first light: about the vertical axis through `pivot` by dx, higher or lower by
/// dy (a spot keeps pointing the same way relative to the pivot).
pub fn drag_light(scene: &mut Scene, pivot: Vec3, dx: f32, dy: f32) {
    let Some(light) = scene.lights.first_mut() else { return };
    let a = dx * TURN;
    let rotation = Mat3::from_rotation_y(a);
    let height = (light.position - pivot).length().max(0.1) * dy * -TURN;
    light.position = pivot + rotation * (light.position - pivot) + Vec3::Y * height;
    if let LightKind::Spot { direction, .. } = &mut light.kind {
        *direction = (rotation * *direction).normalize();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn camera() -> Camera {
        Camera {
            eye: Vec3::new(0.0, 3.5, 5.0),
            target: Vec3::new(0.0, 0.4, 0.0),
            up: Vec3::Y,
            fov_y_deg: 40.0,
            width: 64,
            height: 64,
        }
    }

    #[test]
    fn orbit_keeps_the_target_and_distance_fly_keeps_the_eye() {
        let mut c = camera();
        let dist = (c.eye - c.target).length();
        drag(&mut c, Mode::Orbit, 120.0, 30.0);
        assert_eq!(c.target, camera().target);
        assert!(((c.eye - c.target).length() - dist).abs() < 1e-4);
        assert!((c.eye - camera().eye).length() > 0.5, "the eye moved: {:?}", c.eye);
        let mut f = camera();
        drag(&mut f, Mode::Fly, 120.0, 30.0);
        assert_eq!(f.eye, camera().eye);
        assert!((f.target - camera().target).length() > 0.5);
        // No drag, no change (the angles round-trip).
        let mut z = camera();
        drag(&mut z, Mode::Orbit, 0.0, 0.0);
        assert!((z.eye - camera().eye).length() < 1e-4, "{:?}", z.eye);
    }

    #[test]
    fn dolly_and_fly_move_as_asked() {
        let mut c = camera();
        let d0 = (c.eye - c.target).length();
        dolly(&mut c, 1.0);
        assert!(((c.eye - c.target).length() - 0.9 * d0).abs() < 1e-4);
        let mut f = camera();
        fly(&mut f, 0.0, 0.0, 1.0);
        assert!((f.eye - camera().eye).dot(camera().target - camera().eye) > 0.0, "forward is toward the target");
        assert!(((f.eye - f.target) - (camera().eye - camera().target)).length() < 1e-4);
    }
}
