//! Structs shared with the GPU: one definition each, `#[repr(C)]`, 16-byte members only, sizes
//! checked at compile time. Their GLSL twins live in `shaders_glsl/common/frame.glsl` and
//! `common/mesh_vertex.glsl`; `tests::glsl_mirrors_agree` compares the member lists. Push
//! constants are in `push.rs`.

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
    /// Member (type, name) pairs of a GLSL struct/block body, in order.
    fn glsl_members(src: &str, opener: &str) -> Vec<(String, String)> {
        let start = src.find(opener).expect("block in GLSL") + opener.len();
        let body = &src[start..src[start..].find('}').unwrap() + start];
        body.lines()
            .map(|l| l.split("//").next().unwrap().trim())
            .filter(|l| l.ends_with(';'))
            .map(|l| {
                let mut it = l.trim_end_matches(';').split_whitespace();
                (it.next().unwrap().to_string(), it.next().unwrap().to_string())
            })
            .collect()
    }

    #[test]
    fn glsl_mirrors_agree() {
        let src = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../../shaders_glsl/common/frame.glsl"))
            .unwrap();
        let light: Vec<_> = glsl_members(&src, "struct Light {");
        let want_light = [
            ("vec4", "position"),
            ("vec4", "intensity"),
            ("vec4", "spot"),
            ("vec4", "spot_u"),
            ("vec4", "spot_v"),
            ("vec4", "shadow"),
            ("mat4", "face_view_proj[6]"),
        ];
        assert_eq!(light, want_light.map(|(a, b)| (a.to_string(), b.to_string())).to_vec());
        let frame = glsl_members(&src, "uniform Frame {");
        let want_frame = [
            ("mat4", "view_proj"),
            ("mat4", "inv_view_proj"),
            ("vec4", "eye"),
            ("vec4", "viewport"),
            ("vec4", "background"),
            ("uvec4", "counts"),
            ("vec4", "receiver"),
            ("vec4", "receiver_range"),
            ("Light", "lights[MAX_LIGHTS]"),
        ];
        assert_eq!(frame, want_frame.map(|(a, b)| (a.to_string(), b.to_string())).to_vec());
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
        // Field sizes on the Rust side, in the same order (each vec4 = 16 bytes, mat4 = 64).
        let light_rust = std::mem::size_of::<super::LightUniforms>();
        assert_eq!(light_rust, 6 * 16 + 6 * 64);
        let vs =
            std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../../shaders_glsl/common/mesh_vertex.glsl"))
                .unwrap();
        for (loc, ty) in [(0, "vec3 a_position"), (1, "vec3 a_normal"), (2, "float a_thickness")] {
            assert!(vs.contains(&format!("layout(location = {loc}) in {ty};")), "{ty}");
        }
    }
}
