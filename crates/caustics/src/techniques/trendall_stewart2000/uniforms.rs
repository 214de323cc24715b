//! `PoolUniforms`: everything the pool's passes read, one `#[repr(C)]` struct of 16-byte members
//! whose GLSL twin is `shaders_glsl/trendall_stewart2000/pool.glsl` (`tests` compares them).

use super::adjusted::{Adjustments, Encoding};
use super::kernels::{basis, interface, Kernels};
use super::water_surface::sources;
use crate::scene::{PoolSpec, Scene};
use bytemuck::{Pod, Zeroable};
use glam::Vec3;

/// Wave sources the GPU holds: room for every impulse with its four reflections.
pub const MAX_SOURCES: usize = 256;
const _: () = assert!(crate::scene::pool::MAX_IMPULSES * 5 <= MAX_SOURCES);

#[repr(C)]
#[derive(Clone, Copy, Pod, Zeroable, Debug)]
pub struct PoolUniforms {
    /// n (grid side), kernel side, faithful (1: the 8-bit path), wave sources.
    pub grid: [u32; 4],
    /// The kernel window's centre offset (x, z texels), its half-width r, 0.
    pub kernel: [i32; 4],
    /// Pool side, depth, texel size, half side (m).
    pub pool: [f32; 4],
    /// L_i (the direction light travels, xyz) and L_s.
    pub light: [f32; 4],
    /// n_i / n_t, n_i, n_t, the exponent n.
    pub optics: [f32; 4],
    /// a, epsilon, the bottom's albedo, the time (s).
    pub medium: [f32; 4],
    /// A, K, omega, alpha of h(t, d) (Sec. 4.3).
    pub wave: [f32; 4],
    /// beta, then 0.
    pub wave_damping: [f32; 4],
    /// The expansion basis (xyz each).
    pub basis_x: [f32; 4],
    pub basis_y: [f32; 4],
    pub basis_z: [f32; 4],
    /// Encodings (lo, span) of the faithful path: height, slope.
    pub enc_height_slope: [f32; 4],
    /// cos(theta_i) (lo, span), then 0.
    pub enc_cos: [f32; 4],
    pub enc_normal_lo: [f32; 4],
    pub enc_normal_span: [f32; 4],
    pub enc_gamma_n_lo: [f32; 4],
    pub enc_gamma_n_span: [f32; 4],
    pub enc_lt_lo: [f32; 4],
    pub enc_lt_span: [f32; 4],
    pub enc_direction_lo: [f32; 4],
    pub enc_direction_span: [f32; 4],
    pub enc_convolution_lo: [f32; 4],
    pub enc_convolution_span: [f32; 4],
    /// The final render's camera: right (xyz, tan(fov_y / 2) aspect), up (xyz, tan(fov_y / 2)),
    /// forward (xyz).
    pub cam_right: [f32; 4],
    pub cam_up: [f32; 4],
    pub cam_forward: [f32; 4],
    /// The eye (xyz), then the exposure.
    pub eye: [f32; 4],
    /// Final image width, height; E of flat water in physical units (L_s cos T e^(-eps l)); 0.
    pub view: [f32; 4],
    /// Radiance of the sky the water reflects (rgb).
    pub sky: [f32; 4],
    /// (x, z, time since the impulse, 0) per wave source.
    pub sources: [[f32; 4]; MAX_SOURCES],
}

const _: () = assert!(std::mem::size_of::<PoolUniforms>() == 29 * 16 + MAX_SOURCES * 16);

fn v4(v: Vec3, w: f32) -> [f32; 4] {
    [v.x, v.y, v.z, w]
}

fn lo_span(e: &[Encoding]) -> ([f32; 4], [f32; 4]) {
    let mut lo = [0.0; 4];
    let mut span = [1.0; 4];
    for (i, x) in e.iter().enumerate() {
        lo[i] = x.lo as f32;
        span[i] = x.span as f32;
    }
    (lo, span)
}

/// The physical irradiance on the bottom under flat water, for the final render's scale:
/// L_s cos(theta_i) T e^(-epsilon d / cos(theta_t)) (the receiver map is E / E_flat).
pub fn flat_irradiance(pool: &PoolSpec) -> f64 {
    let it = interface(pool);
    let ci = -pool.light_direction.y;
    let path = pool.depth / it.cos_transmitted(ci);
    pool.light_radiance * ci * it.transmittance(ci) * (-pool.extinction * path).exp()
}

/// The uniforms of `scene`'s pool on an `n` x `n` grid, with kernels `k`; `faithful` selects
/// the 8-bit path's encodings `adj`.
pub fn pool_uniforms(
    scene: &Scene,
    pool: &PoolSpec,
    n: u32,
    k: &Kernels,
    adj: &Adjustments,
    faithful: bool,
) -> PoolUniforms {
    let b = basis(pool);
    let it = interface(pool);
    let src = sources(pool);
    let mut sources_out = [[0.0f32; 4]; MAX_SOURCES];
    for (o, s) in sources_out.iter_mut().zip(&src) {
        *o = [s.position.x as f32, s.position.y as f32, s.age as f32, 0.0];
    }
    let cam = &scene.camera;
    let forward = (cam.target - cam.eye).normalize();
    let right = forward.cross(cam.up).normalize();
    let up = right.cross(forward);
    let tan_half = (0.5 * cam.fov_y_deg.to_radians()).tan();
    let (cl, cs) = lo_span(&adj.convolution);
    let (nl, ns) = lo_span(&adj.normal);
    let (gl, gs) = lo_span(&adj.gamma_n);
    let (ll, ls) = lo_span(&adj.lt);
    let (dl, ds) = lo_span(&adj.direction);
    let w = &pool.wave;
    let f = |v: f64| v as f32;
    let d = pool.light_direction.as_vec3();
    PoolUniforms {
        grid: [n, k.side as u32, faithful as u32, src.len().min(MAX_SOURCES) as u32],
        kernel: [k.offset[0], k.offset[1], (k.side / 2) as i32, 0],
        pool: [f(pool.side), f(pool.depth), f(pool.side / n as f64), f(pool.half())],
        light: v4(d, f(pool.light_radiance)),
        optics: [f(it.eta()), f(pool.ior_air), f(pool.ior), f(pool.exponent)],
        medium: [f(pool.scattering), f(pool.extinction), f(pool.albedo), f(pool.time)],
        wave: [f(w.amplitude), f(w.wave_number), f(w.angular_frequency), f(w.time_damping)],
        wave_damping: [f(w.distance_damping), 0.0, 0.0, 0.0],
        basis_x: v4(b.x.as_vec3(), 0.0),
        basis_y: v4(b.y.as_vec3(), 0.0),
        basis_z: v4(b.z.as_vec3(), 0.0),
        enc_height_slope: [f(adj.height.lo), f(adj.height.span), f(adj.slope.lo), f(adj.slope.span)],
        enc_cos: [f(adj.cos_i.lo), f(adj.cos_i.span), 0.0, 0.0],
        enc_normal_lo: nl,
        enc_normal_span: ns,
        enc_gamma_n_lo: gl,
        enc_gamma_n_span: gs,
        enc_lt_lo: ll,
        enc_lt_span: ls,
        enc_direction_lo: dl,
        enc_direction_span: ds,
        enc_convolution_lo: cl,
        enc_convolution_span: cs,
        cam_right: v4(right, tan_half * cam.aspect()),
        cam_up: v4(up, tan_half),
        cam_forward: v4(forward, 0.0),
        eye: v4(cam.eye, scene.render.exposure),
        view: [cam.width as f32, cam.height as f32, f(flat_irradiance(pool)), 0.0],
        sky: v4(scene.render.background, 0.0),
        sources: sources_out,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::mem::offset_of;

    /// (GLSL type, name) of each member of the `PoolUniforms` block in pool.glsl, in order.
    fn glsl_members() -> Vec<(String, String)> {
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../shaders_glsl/trendall_stewart2000/pool.glsl");
        let src = std::fs::read_to_string(path).expect("pool.glsl");
        let start = src.find("uniform PoolUniforms {").expect("the block") + "uniform PoolUniforms {".len();
        let body = &src[start..start + src[start..].find('}').expect("its end")];
        body.lines()
            .map(|l| l.split("//").next().unwrap_or("").trim())
            .filter(|l| l.ends_with(';'))
            .map(|l| {
                let mut it = l.trim_end_matches(';').split_whitespace();
                (it.next().unwrap_or("").to_string(), it.next().unwrap_or("").to_string())
            })
            .collect()
    }

    #[test]
    fn the_glsl_block_is_the_twin_of_the_struct() {
        // The Rust members with their offsets; every one is 16 bytes (std140 vec4s), in order.
        let rust = [
            ("uvec4", "grid", offset_of!(PoolUniforms, grid)),
            ("ivec4", "kernel", offset_of!(PoolUniforms, kernel)),
            ("vec4", "pool", offset_of!(PoolUniforms, pool)),
            ("vec4", "light", offset_of!(PoolUniforms, light)),
            ("vec4", "optics", offset_of!(PoolUniforms, optics)),
            ("vec4", "medium", offset_of!(PoolUniforms, medium)),
            ("vec4", "wave", offset_of!(PoolUniforms, wave)),
            ("vec4", "wave_damping", offset_of!(PoolUniforms, wave_damping)),
            ("vec4", "basis_x", offset_of!(PoolUniforms, basis_x)),
            ("vec4", "basis_y", offset_of!(PoolUniforms, basis_y)),
            ("vec4", "basis_z", offset_of!(PoolUniforms, basis_z)),
            ("vec4", "enc_height_slope", offset_of!(PoolUniforms, enc_height_slope)),
            ("vec4", "enc_cos", offset_of!(PoolUniforms, enc_cos)),
            ("vec4", "enc_normal_lo", offset_of!(PoolUniforms, enc_normal_lo)),
            ("vec4", "enc_normal_span", offset_of!(PoolUniforms, enc_normal_span)),
            ("vec4", "enc_gamma_n_lo", offset_of!(PoolUniforms, enc_gamma_n_lo)),
            ("vec4", "enc_gamma_n_span", offset_of!(PoolUniforms, enc_gamma_n_span)),
            ("vec4", "enc_lt_lo", offset_of!(PoolUniforms, enc_lt_lo)),
            ("vec4", "enc_lt_span", offset_of!(PoolUniforms, enc_lt_span)),
            ("vec4", "enc_direction_lo", offset_of!(PoolUniforms, enc_direction_lo)),
            ("vec4", "enc_direction_span", offset_of!(PoolUniforms, enc_direction_span)),
            ("vec4", "enc_convolution_lo", offset_of!(PoolUniforms, enc_convolution_lo)),
            ("vec4", "enc_convolution_span", offset_of!(PoolUniforms, enc_convolution_span)),
            ("vec4", "cam_right", offset_of!(PoolUniforms, cam_right)),
            ("vec4", "cam_up", offset_of!(PoolUniforms, cam_up)),
            ("vec4", "cam_forward", offset_of!(PoolUniforms, cam_forward)),
            ("vec4", "eye", offset_of!(PoolUniforms, eye)),
            ("vec4", "view", offset_of!(PoolUniforms, view)),
            ("vec4", "sky", offset_of!(PoolUniforms, sky)),
            ("vec4", "sources[MAX_SOURCES]", offset_of!(PoolUniforms, sources)),
        ];
        for (i, (_, name, offset)) in rust.iter().enumerate() {
            assert_eq!(*offset, 16 * i, "{name}");
        }
        let glsl = glsl_members();
        let want: Vec<(String, String)> = rust.iter().map(|(t, n, _)| (t.to_string(), n.to_string())).collect();
        assert_eq!(glsl, want);
        let src = std::fs::read_to_string(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../shaders_glsl/trendall_stewart2000/pool.glsl"
        ))
        .expect("pool.glsl");
        assert!(src.contains(&format!("#define MAX_SOURCES {MAX_SOURCES}")));
    }
}
