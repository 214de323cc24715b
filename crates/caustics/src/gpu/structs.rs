//! Structs shared with the GPU: one definition each, `#[repr(C)]`, 16-byte members only, sizes
//! checked at compile time. Their GLSL twins live in `shaders_glsl/common/frame.glsl` and
//! `common/mesh_vertex.glsl`; `tests::glsl_mirrors_agree` compares the members' offsets with
//! the ones glslang gives them. Push constants are in `push.rs`.

use bytemuck::{Pod, Zeroable};

pub const MAX_LIGHTS: usize = 4;

#[repr(C)]
#[derive(Clone, Copy, Pod, Zeroable, Debug)]
pub struct LightUniforms {
    pub position: [f32; 4],
    pub intensity: [f32; 4],
    pub spot: [f32; 4],
    pub spot_u: [f32; 4],
    pub spot_v: [f32; 4],
    pub shadow: [f32; 4],
    pub face_view_proj: [[f32; 16]; 6],
}

#[repr(C)]
#[derive(Clone, Copy, Pod, Zeroable, Debug)]
pub struct FrameUniforms {
    pub view_proj: [f32; 16],
    pub inv_view_proj: [f32; 16],
    pub eye: [f32; 4],
    pub viewport: [f32; 4],
    pub background: [f32; 4],
    pub counts: [u32; 4],
    pub receiver: [f32; 4],
    pub receiver_range: [f32; 4],
    pub lights: [LightUniforms; MAX_LIGHTS],
}

/// One mesh vertex: world position, outward normal, Wyman 2005 thickness d_N.
#[repr(C)]
#[derive(Clone, Copy, Pod, Zeroable, Debug, Default)]
pub struct MeshVertex {
    pub position: [f32; 3],
    pub normal: [f32; 3],
    pub thickness: f32,
}

pub const MATERIAL_DIFFUSE: u32 = 0;
pub const MATERIAL_REFRACTIVE: u32 = 1;
pub const MATERIAL_REFLECTIVE: u32 = 2;

const _: () = assert!(std::mem::size_of::<LightUniforms>() == 6 * 16 + 6 * 64);
const _: () = assert!(std::mem::size_of::<FrameUniforms>() == 2 * 64 + 6 * 16 + MAX_LIGHTS * 480);
const _: () = assert!(std::mem::size_of::<MeshVertex>() == 28);

#[cfg(test)]
mod tests {
    use vkcore::ShaderCompiler;

    /// (name, `offset_of!`) of every field of struct `$ty`, in declaration order.
    macro_rules! rust_fields {
        ($ty:ident { $($field:ident),* $(,)? }) => {{
            // Names every field or does not compile: the list cannot fall behind the struct.
            let super::$ty { $($field: _),* } = <super::$ty as bytemuck::Zeroable>::zeroed();
            vec![$((stringify!($field).to_string(), std::mem::offset_of!(super::$ty, $field) as u32)),*]
        }};
    }

    #[test]
    fn glsl_mirrors_agree() {
        // Each struct's members, by name, at the offsets std140 gives them in a shader that
        // reads the frame's lights (shadow_map.vert: `frame.lights[..].face_view_proj[..]`).
        let sh = ShaderCompiler::new(&crate::render::shader_root()).unwrap();
        let spirv = sh.compile("shadow/shadow_map.vert", &[]).unwrap();
        let rust_light =
            rust_fields!(LightUniforms { position, intensity, spot, spot_u, spot_v, shadow, face_view_proj });
        let rust_frame = rust_fields!(FrameUniforms {
            view_proj,
            inv_view_proj,
            eye,
            viewport,
            background,
            counts,
            receiver,
            receiver_range,
            lights
        });
        for (name, rust) in [("Light", &rust_light), ("Frame", &rust_frame)] {
            let layouts = spirv.struct_layouts(name);
            assert!(!layouts.is_empty(), "no laid-out struct `{name}` in shadow_map.vert");
            for glsl in layouts {
                let glsl: Vec<(String, u32)> = glsl.into_iter().map(|m| (m.name, m.offset)).collect();
                assert_eq!(&glsl, rust, "`{name}`: GLSL (std140) against Rust (repr(C)) members and offsets");
            }
        }
        // Arrays step as far in both: `lights[i]` and `face_view_proj[i]` line up.
        let stride = |name: &str, member: &str| {
            let layout = spirv.struct_layouts(name).remove(0);
            layout.into_iter().find(|m| m.name == member).and_then(|m| m.array_stride).expect("an array member")
                as usize
        };
        assert_eq!(stride("Frame", "lights"), std::mem::size_of::<super::LightUniforms>());
        assert_eq!(stride("Light", "face_view_proj"), std::mem::size_of::<[f32; 16]>());
        let src = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../../shaders_glsl/common/frame.glsl"))
            .unwrap();
        assert!(src.contains(&format!("#define MAX_LIGHTS {}", super::MAX_LIGHTS)));
        let mesh =
            std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../../shaders_glsl/common/materials.glsl"))
                .unwrap();
        for (name, value) in [
            ("MATERIAL_DIFFUSE", super::MATERIAL_DIFFUSE),
            ("MATERIAL_REFRACTIVE", super::MATERIAL_REFRACTIVE),
            ("MATERIAL_REFLECTIVE", super::MATERIAL_REFLECTIVE),
        ] {
            assert!(mesh.contains(&format!("#define {name} {value}u")), "{name}");
        }
        let vs =
            std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../../shaders_glsl/common/mesh_vertex.glsl"))
                .unwrap();
        for (loc, ty) in [(0, "vec3 a_position"), (1, "vec3 a_normal"), (2, "float a_thickness")] {
            assert!(vs.contains(&format!("layout(location = {loc}) in {ty};")), "{ty}");
        }
    }
}
