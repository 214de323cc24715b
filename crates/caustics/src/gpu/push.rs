//! Push constants: one struct per kind of pass, each the twin of a GLSL
//! `layout(push_constant)` block of the same name and members (`tests` compares them through
//! the SPIR-V of every shader that declares one).

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
    /// The GPU photon tracer (`photon_trace/trace.comp`).
    pub struct PhotonTraceConstants {
        /// xyz centre, w radius: the specular objects' bounding sphere.
        pub sphere: [f32; 4],
        pub light: u32,
        pub seed: u32,
        pub max_bounces: u32,
        /// `PHOTON_TRACE_*`.
        pub flags: u32,
        /// Ray offset against self-intersection (world units).
        pub eps: f32,
        /// How far from the receiver plane a photon still lands on it (the reference's).
        pub receiver_tolerance: f32,
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

push_constants! {
    /// Building one level of the photon hierarchy (`wyman2008/build.comp`).
    pub struct BuildConstants {
        /// k >= 1.
        pub level: u32,
        pub light: u32,
        /// The photon buffer side N.
        pub photon_side: u32,
    }
}

push_constants! {
    /// One step of the hierarchical traversal (`wyman2008/traverse.glsl`).
    pub struct TraverseConstants {
        pub light: u32,
        /// 1 when convergence is tested at this level.
        pub cluster: u32,
        /// The photon buffer side N.
        pub photon_side: u32,
    }
}

push_constants! {
    /// The `splats` dump (`wyman2008/splat_footprints.comp`).
    pub struct FootprintConstants {
        /// Entries in the traversal's final list.
        pub entries: u32,
        pub light: u32,
    }
}

push_constants! {
    /// One level of the coverage pyramid of adaptive caustic maps' geometry buffers
    /// (`wyman_nichols2009/coverage.comp`).
    pub struct CoverageConstants {
        /// m: 0 from the geometry buffers, else from level m - 1.
        pub level: u32,
    }
}

push_constants! {
    /// One kernel of a step of the adaptive traversal (`wyman_nichols2009/adaptive.glsl`).
    pub struct AdaptiveConstants {
        pub light: u32,
        /// k: the step's photons lie on the (64 2^k)² grid.
        pub level: u32,
        /// L: the last level (64 2^L photons per side).
        pub finest: u32,
        /// 1 when the step tests convergence (max-error metric, from the 512² level on).
        pub converge: u32,
    }
}

push_constants! {
    /// A batch's input of the adaptive traversal (`wyman_nichols2009/adaptive_batch.comp`).
    pub struct BatchConstants {
        /// The batch's first cluster of level B.
        pub first: u32,
        /// Clusters per batch.
        pub size: u32,
        /// 1 on the transform-feedback path (byte counts).
        pub xfb: u32,
    }
}

push_constants! {
    /// The adaptive traversal's per-level counts (`wyman_nichols2009/adaptive_counts.comp`).
    pub struct CountConstants {
        /// The next level's slot (u32::MAX: none).
        pub cluster_slot: u32,
        pub photon_slot: u32,
        /// 1 on the transform-feedback path (byte counts).
        pub xfb: u32,
    }
}

push_constants! {
    /// Wyman & Davis 2006's eye-space points, caustic quads and gathers
    /// (`shaders_glsl/wyman_davis2006/image_space.glsl`).
    pub struct ImageSpaceConstants {
        /// World to the view's clip space (the eye's, or the orthographic receiver view).
        pub view_proj: [f32; 16],
        /// A photon is on a pixel's surface within x * (distance to the eye) + y metres.
        pub tolerance: [f32; 4],
        /// xyz: the eye; w: 1 for an orthographic view.
        pub eye: [f32; 4],
        pub light: u32,
        /// The equation lighting the photons: 9, 10, 11 (points, gathers) or 3, 4 (quads).
        pub lighting: u32,
        /// The history layer this frame writes (temporal filter).
        pub slot: u32,
        /// History layers that hold a frame (1..=4).
        pub frames: u32,
        /// The gather's half-width (3: 7x7; 0: points).
        pub radius: u32,
        /// Neighbourhoods with fewer photons are discarded.
        pub min_photons: u32,
        /// The photon buffer's side N.
        pub photon_side: u32,
        /// The view's first history layer.
        pub history_base: u32,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use vkcore::{check_push_constants, PushConstants, ShaderCompiler};

    /// Checks `T` against every (shader, defines) variant that declares its block.
    fn check<T: PushConstants>(variants: &[(&str, &[(&str, &str)])]) {
        let sh = ShaderCompiler::new(&crate::render::shader_root()).unwrap();
        for (file, defines) in variants {
            let spirv = sh.compile(file, defines).unwrap();
            if let Err(e) = check_push_constants::<T>(&spirv) {
                panic!("{file} {defines:?}: {e}");
            }
        }
    }

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
    fn photon_trace_constants() {
        check::<PhotonTraceConstants>(&[
            ("photon_trace/trace.comp", &[]),
            ("photon_trace/trace.comp", &[("RECEIVER_DEPOSIT", "1")]),
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

    #[test]
    fn build_constants() {
        check::<BuildConstants>(&[("wyman2008/build.comp", &[])]);
    }

    #[test]
    fn traverse_constants() {
        check::<TraverseConstants>(&[("wyman2008/traverse.geom", &[]), ("wyman2008/traverse.comp", &[])]);
    }

    #[test]
    fn footprint_constants() {
        check::<FootprintConstants>(&[("wyman2008/splat_footprints.comp", &[])]);
    }

    #[test]
    fn adaptive_constants() {
        let mut variants: Vec<(&str, &[(&str, &str)])> = vec![("wyman_nichols2009/adaptive_traverse.comp", &[])];
        let kernels: [&[(&str, &str)]; 5] = [
            &[("SUBDIVIDE", "1")],
            &[("EMIT", "1")],
            &[("HITS", "1")],
            &[("FROM_HITS", "1"), ("CONVERGED", "1")],
            &[("FROM_HITS", "1"), ("REFINE", "1")],
        ];
        variants.extend(kernels.iter().map(|d| ("wyman_nichols2009/adaptive_step.geom", *d)));
        check::<AdaptiveConstants>(&variants);
        check::<CoverageConstants>(&[("wyman_nichols2009/coverage.comp", &[])]);
        check::<BatchConstants>(&[("wyman_nichols2009/adaptive_batch.comp", &[])]);
        check::<CountConstants>(&[("wyman_nichols2009/adaptive_counts.comp", &[])]);
    }

    #[test]
    fn image_space_constants() {
        let light: &[(&str, &str)] = &[("LIGHT_SPACE", "1")];
        check::<ImageSpaceConstants>(&[
            ("wyman_davis2006/photons.vert", &[]),
            ("wyman_davis2006/photons.frag", &[]),
            ("wyman_davis2006/photons.vert", light),
            ("wyman_davis2006/photons.frag", light),
            ("wyman_davis2006/quads.vert", &[]),
            ("wyman_davis2006/quads.frag", &[]),
            ("wyman_davis2006/quads.vert", light),
            ("wyman_davis2006/quads.frag", light),
            ("wyman_davis2006/gather.comp", &[]),
            ("wyman_davis2006/gather.comp", light),
        ]);
    }

    /// The reflection the checks rely on tells a renamed or reordered member apart.
    #[test]
    fn a_renamed_or_reordered_member_fails() {
        mod renamed {
            vkcore::push_constants! {
                pub struct FootprintConstants { pub entries: u32, pub lamp: u32 }
            }
        }
        mod reordered {
            vkcore::push_constants! {
                pub struct FootprintConstants { pub light: u32, pub entries: u32 }
            }
        }
        let sh = ShaderCompiler::new(&crate::render::shader_root()).unwrap();
        let spirv = sh.compile("wyman2008/splat_footprints.comp", &[]).unwrap();
        assert!(check_push_constants::<FootprintConstants>(&spirv).is_ok());
        let renamed = check_push_constants::<renamed::FootprintConstants>(&spirv).unwrap_err();
        assert!(renamed.contains("lamp"), "{renamed}");
        assert!(check_push_constants::<reordered::FootprintConstants>(&spirv).is_err());
    }
}
