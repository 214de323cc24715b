//! Push constants of the passes several papers share (mesh draws, the point and compute
//! splats): one struct per kind of pass, each the twin of a GLSL `layout(push_constant)` block
//! of the same name and members (`tests` compares them through the SPIR-V of every shader that
//! declares one). A paper's own are in its folder (`techniques::<paper>::push`), checked the
//! same way ([`check`]).

use vkcore::push_constants;

push_constants! {
    /// Every mesh draw (`shaders_glsl/common/mesh_constants.glsl`).
    pub struct MeshConstants {
        /// Diffuse albedo, transmission colour or specular colour.
        pub colour: [f32; 4],
        /// RGB index of refraction (refractive).
        pub ior: [f32; 4],
        /// `MATERIAL_*`.
        pub material: u32,
        /// The light a pass from a light (or the shadow map) renders for.
        pub light: u32,
        /// Vertex photons: the mesh's first photon.
        pub first_photon: u32,
        /// The mesh's index in the scene (which object covers a texel of the light-space
        /// geometry buffers of adaptive caustic maps).
        pub object: u32,
    }
}

push_constants! {
    /// The point splat (`shared/splat.vert`).
    pub struct SplatConstants {
        pub light: u32,
        /// The instanced fetch from the photon texture: vertices per instance.
        pub vertices_per_instance: u32,
    }
}

push_constants! {
    /// The compute splat (`shared/splat.comp`).
    pub struct ComputeSplatConstants {
        /// From the photon texture: its texels, one invocation each.
        pub photon_texels: u32,
        pub light: u32,
    }
}

/// Checks `T` against every (shader, defines) variant that declares its block.
#[cfg(test)]
pub(crate) fn check<T: vkcore::PushConstants>(variants: &[(&str, &[(&str, &str)])]) {
    let sh = vkcore::ShaderCompiler::new(&crate::render::shader_root()).unwrap();
    for (file, defines) in variants {
        let spirv = sh.compile(file, defines).unwrap();
        if let Err(e) = vkcore::check_push_constants::<T>(&spirv) {
            panic!("{file} {defines:?}: {e}");
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mesh_constants() {
        let photon_view: &[(&str, &str)] = &[("PHOTON_VIEW", "1")];
        check::<MeshConstants>(&[
            ("shadow/shadow_map.vert", &[]),
            ("shadow/shadow_map.frag", &[]),
            ("eye/background.frag", &[]),
            ("eye/front_faces.frag", &[]),
            ("wyman_nichols2009/deferred_refraction.frag", &[]),
            ("shared/light_mesh.vert", &[]),
            ("shared/light_mesh.vert", photon_view),
            ("shared/back_faces.frag", &[]),
            ("shared/photon_buffer.frag", &[]),
            ("shah2007/vertex_photons.vert", &[]),
            ("wyman_nichols2009/light_geometry.geom", &[]),
            ("wyman_nichols2009/light_geometry.frag", &[]),
        ]);
    }

    #[test]
    fn splat_constants() {
        check::<SplatConstants>(&[
            ("shared/splat.vert", &[]),
            ("shared/splat.vert", &[("PHOTON_VERTEX_ARRAY", "1")]),
            ("shared/splat.vert", &[("PHOTON_VERTEX_ARRAY", "1"), ("PHOTON_HALF", "1")]),
            ("shared/splat.vert", &[("HIERARCHY", "1")]),
            ("shared/splat.vert", &[("ADAPTIVE_PHOTONS", "1")]),
        ]);
    }

    #[test]
    fn compute_splat_constants() {
        check::<ComputeSplatConstants>(&[
            ("shared/splat.comp", &[("ENTRY_BYTES", "4")]),
            ("shared/splat.comp", &[("ENTRY_BYTES", "4"), ("HIERARCHY", "1")]),
            ("shared/splat.comp", &[("ENTRY_BYTES", "4"), ("HIERARCHY", "1"), ("XFB", "1")]),
            ("shared/splat.comp", &[("ENTRY_BYTES", "32"), ("ADAPTIVE_PHOTONS", "1")]),
            ("shared/splat.comp", &[("ENTRY_BYTES", "32"), ("ADAPTIVE_PHOTONS", "1"), ("XFB", "1")]),
        ]);
    }
}
