//! Scene data on the GPU: meshes (with Wyman 2005 per-vertex thickness for refractors), camera
//! and light matrices, and the frame uniforms.

use super::push::MeshConstants;
use super::structs::*;
use crate::bvh::vertex_thickness_memo;
use crate::scene::{LightKind, MaterialKind, Scene};
use anyhow::{Context as _, Result};
use glam::{Mat4, Vec3};
use vkcore::{Access, Buffer, Cmd, Context, Use};

/// One object's buffers and draw constants.
pub struct GpuMesh {
    pub name: String,
    pub vertices: Buffer,
    pub indices: Buffer,
    pub index_count: u32,
    pub constants: MeshConstants,
    /// Wyman 2005 thickness per vertex (unchanged by rigid motion, kept for re-uploads).
    pub thickness: std::sync::Arc<[f32]>,
}

/// The GPU vertices of `m` with the given per-vertex thickness.
pub fn mesh_vertices(m: &crate::scene::Mesh, thickness: &[f32]) -> Vec<MeshVertex> {
    (0..m.positions.len())
        .map(|i| MeshVertex {
            position: m.positions[i].to_array(),
            normal: m.normals[i].to_array(),
            thickness: thickness.get(i).copied().unwrap_or(0.0),
        })
        .collect()
}

impl GpuMesh {
    pub fn kind(&self) -> u32 {
        self.constants.material
    }

    /// Records an indexed draw of this mesh with its constants for `light`.
    pub fn draw(&self, cmd: &mut Cmd, instances: u32, light: u32) -> vkcore::Result<()> {
        cmd.push(&MeshConstants { light, ..self.constants })?;
        cmd.bind_vertex_buffer(&self.vertices, 0)?;
        cmd.bind_index_buffer(&self.indices)?;
        cmd.draw_indexed(self.index_count, instances, 0);
        Ok(())
    }
}

/// The vertex and index buffers of `meshes`, read as vertex input.
pub fn mesh_uses(meshes: &[GpuMesh]) -> Vec<Use<'_>> {
    meshes
        .iter()
        .flat_map(|m| [Use::buffer(&m.vertices, Access::VERTEX_INPUT), Use::buffer(&m.indices, Access::VERTEX_INPUT)])
        .collect()
}

pub fn upload_meshes(ctx: &Context, scene: &Scene) -> Result<Vec<GpuMesh>> {
    let mut out = vec![];
    for (object, obj) in scene.objects.iter().enumerate() {
        let m = &obj.mesh;
        let (kind, colour, ior) = match &scene.material_of(obj).kind {
            MaterialKind::Diffuse { albedo } => (MATERIAL_DIFFUSE, *albedo, Vec3::ONE),
            MaterialKind::Refractive { ior, transmission } => (MATERIAL_REFRACTIVE, *transmission, *ior),
            MaterialKind::Reflective { specular } => (MATERIAL_REFLECTIVE, *specular, Vec3::ONE),
        };
        let thickness = if kind == MATERIAL_REFRACTIVE {
            vertex_thickness_memo(&m.positions, &m.normals, &m.indices)
        } else {
            vec![0.0; m.positions.len()].into()
        };
        let vertices = mesh_vertices(m, &thickness);
        let vb = ctx
            .buffer_with_data(&format!("{} vertices", obj.name), bytemuck::cast_slice(&vertices))
            .with_context(|| format!("uploading object `{}`", obj.name))?;
        let ib = ctx
            .buffer_with_data(&format!("{} indices", obj.name), bytemuck::cast_slice(&m.indices))
            .with_context(|| format!("uploading object `{}`", obj.name))?;
        out.push(GpuMesh {
            thickness,
            name: obj.name.clone(),
            vertices: vb,
            indices: ib,
            index_count: m.indices.len() as u32,
            constants: MeshConstants {
                colour: colour.extend(1.0).to_array(),
                ior: ior.extend(1.0).to_array(),
                material: kind,
                object: object as u32,
                ..Default::default()
            },
        });
    }
    Ok(out)
}

/// Vulkan-style projection: depth in [0, 1], y flipped so that image row 0 is the top of the view
/// (and world-CCW triangles stay counter-clockwise in framebuffer space).
pub fn perspective(fov_y_rad: f32, aspect: f32, near: f32, far: f32) -> Mat4 {
    let mut p = Mat4::perspective_rh(fov_y_rad, aspect, near, far);
    p.y_axis.y = -p.y_axis.y;
    p
}

/// Directions and up vectors of the six shadow-map faces, +X -X +Y -Y +Z -Z; the lookup in
/// `common/lighting.glsl` uses the same matrices, so any consistent choice works.
const FACES: [(Vec3, Vec3); 6] = [
    (Vec3::X, Vec3::Y),
    (Vec3::NEG_X, Vec3::Y),
    (Vec3::Y, Vec3::Z),
    (Vec3::NEG_Y, Vec3::Z),
    (Vec3::Z, Vec3::Y),
    (Vec3::NEG_Z, Vec3::Y),
];

pub fn frame_uniforms(scene: &Scene) -> FrameUniforms {
    let (lo, hi) = scene.bounds();
    let diag = (hi - lo).length().max(1e-3);
    let centre = 0.5 * (lo + hi);
    let cam = &scene.camera;
    let view = Mat4::look_at_rh(cam.eye, cam.target, cam.up);
    let far = cam.eye.distance(centre) + diag;
    let near = (far * 1e-4).max(1e-3);
    let proj = perspective(cam.fov_y_deg.to_radians(), cam.aspect(), near, far);
    let view_proj = proj * view;
    let mut lights = [LightUniforms::zeroed(); MAX_LIGHTS];
    for (l, (light, u)) in scene.lights.iter().zip(lights.iter_mut()).enumerate() {
        let far = light.position.distance(centre) + diag;
        let near = (far * 1e-4).max(1e-3);
        let res = scene.render.shadow_map_resolution as f32;
        let face_proj = perspective(std::f32::consts::FRAC_PI_2, 1.0, near, far);
        for (f, (dir, up)) in FACES.iter().enumerate() {
            let v = Mat4::look_at_rh(light.position, light.position + *dir, *up);
            u.face_view_proj[f] = (face_proj * v).to_cols_array();
        }
        u.position = light.position.extend(0.0).to_array();
        u.intensity = light.intensity.extend(0.0).to_array();
        u.shadow = [near, far, std::f32::consts::FRAC_PI_2 / res, (6 * l) as f32];
        if let LightKind::Spot { direction, cone_angle_deg, texture } = &light.kind {
            u.position[3] = 1.0;
            u.intensity[3] = if texture.is_some() { 1.0 } else { 0.0 };
            // The axes the reference projects the texture with too (scene::spot_projector).
            let (axis_u, axis_v, cos_cone) = crate::scene::spot_projector::cone_axes(*direction, *cone_angle_deg);
            u.spot = direction.extend(cos_cone).to_array();
            u.spot_u = axis_u.extend(0.0).to_array();
            u.spot_v = axis_v.extend(0.0).to_array();
        }
    }
    let (receiver, range) = match &scene.receiver_map {
        Some(r) => {
            ([r.plane_y, r.resolution as f32, 0.0, 0.0], [r.x_range[0], r.x_range[1], r.z_range[0], r.z_range[1]])
        }
        None => ([0.0; 4], [0.0; 4]),
    };
    FrameUniforms {
        view_proj: view_proj.to_cols_array(),
        inv_view_proj: view_proj.inverse().to_cols_array(),
        eye: cam.eye.extend(1.0).to_array(),
        viewport: [cam.width as f32, cam.height as f32, 1.0 / cam.width as f32, 1.0 / cam.height as f32],
        background: scene.render.background.extend(0.0).to_array(),
        counts: [scene.lights.len().min(MAX_LIGHTS) as u32, 0, 0, 0],
        receiver,
        receiver_range: range,
        lights,
    }
}

use bytemuck::Zeroable;

/// Spot-light textures resampled to one size, one layer per light (white where none).
pub const SPOT_TEXTURE_SIZE: u32 = crate::scene::spot_projector::SIZE;

pub fn spot_texture_layers(scene: &Scene) -> Result<Vec<f32>> {
    let n = SPOT_TEXTURE_SIZE as usize;
    let layers = scene.lights.len().clamp(1, MAX_LIGHTS);
    let mut out = vec![1.0f32; layers * n * n * 4];
    for (l, light) in scene.lights.iter().take(MAX_LIGHTS).enumerate() {
        if let LightKind::Spot { texture: Some(path), .. } = &light.kind {
            out[l * n * n * 4..(l + 1) * n * n * 4].copy_from_slice(&crate::scene::spot_projector::resample(path)?);
        }
    }
    Ok(out)
}

/// Per specular object: a third of the area of the triangles around each vertex (the surface a
/// vertex photon stands for, Shah et al.'s vertex tracing); None for diffuse objects.
pub fn vertex_areas(ctx: &Context, scene: &Scene) -> Result<Vec<Option<Buffer>>> {
    scene
        .objects
        .iter()
        .map(|o| {
            if matches!(scene.material_of(o).kind, MaterialKind::Diffuse { .. }) {
                return Ok(None);
            }
            let m = &o.mesh;
            let mut areas = vec![0f32; m.positions.len()];
            for t in m.triangles() {
                let [a, b, c] = t.map(|i| m.positions[i]);
                let third = (b - a).cross(c - a).length() / 6.0;
                for i in t {
                    areas[i] += third;
                }
            }
            Ok(Some(ctx.buffer_with_data(&format!("{} vertex areas", o.name), bytemuck::cast_slice(&areas))?))
        })
        .collect()
}
