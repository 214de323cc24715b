//! A little SPIR-V reflection: the push-constant block's name and its members' names and byte
//! offsets, and any laid-out struct's members with their offsets and array strides, read from
//! the debug names (OpName, OpMemberName) and Offset and ArrayStride decorations that glslang
//! writes, enough to check a `#[repr(C)]` struct against its GLSL twin; and the
//! descriptor bindings of set 0 with their names and kinds, from which a pipeline's descriptor
//! set layout is made and against which a pass's binds are checked by name (`bind.rs`).

use crate::pipeline::BindingKind;
use crate::shader::Spirv;
use std::collections::HashMap;

const OP_NAME: u32 = 5;
const OP_MEMBER_NAME: u32 = 6;
const OP_TYPE_POINTER: u32 = 32;
const OP_VARIABLE: u32 = 59;
const OP_DECORATE: u32 = 71;
const OP_MEMBER_DECORATE: u32 = 72;
const OP_TYPE_IMAGE: u32 = 25;
const OP_TYPE_SAMPLED_IMAGE: u32 = 27;
const OP_TYPE_ARRAY: u32 = 28;
const OP_TYPE_ACCELERATION_STRUCTURE: u32 = 5341;
const OP_TYPE_STRUCT: u32 = 30;
const STORAGE_UNIFORM_CONSTANT: u32 = 0;
const STORAGE_UNIFORM: u32 = 2;
const STORAGE_PUSH_CONSTANT: u32 = 9;
const STORAGE_BUFFER: u32 = 12;
const DECORATION_BLOCK: u32 = 2;
const DECORATION_ARRAY_STRIDE: u32 = 6;
const DECORATION_BUFFER_BLOCK: u32 = 3;
const DECORATION_BINDING: u32 = 33;
const DECORATION_DESCRIPTOR_SET: u32 = 34;
const DECORATION_OFFSET: u32 = 35;

/// One descriptor binding a shader declares in set 0.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ReflectedBinding {
    /// `layout(binding = N)`.
    pub binding: u32,
    /// The variable's name (`uniform sampler2D photon_position` -> `photon_position`), or the
    /// block's where its instance has none (`buffer Photons { .. };` -> `Photons`).
    pub name: String,
    pub kind: BindingKind,
}

/// One member of a laid-out struct (see [`Spirv::struct_layouts`]).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ReflectedMember {
    pub name: String,
    /// Byte offset in the struct (std140, std430 or push-constant rules, as declared).
    pub offset: u32,
    /// For an array, the bytes from one element to the next.
    pub array_stride: Option<u32>,
}

/// A nul-terminated UTF-8 string packed little-endian into words.
fn string(words: &[u32]) -> String {
    let bytes: Vec<u8> = words.iter().flat_map(|w| w.to_le_bytes()).take_while(|&b| b != 0).collect();
    String::from_utf8_lossy(&bytes).into_owned()
}

/// Each instruction as (opcode, operands).
fn instructions(words: &[u32]) -> impl Iterator<Item = (u32, &[u32])> {
    let mut at = 5; // after the header
    std::iter::from_fn(move || {
        let first = *words.get(at)?;
        let (count, op) = ((first >> 16) as usize, first & 0xffff);
        let operands = words.get(at + 1..at + count.max(1))?;
        at += count.max(1);
        Some((op, operands))
    })
}

impl Spirv {
    /// The id of the push-constant block's struct type, if the shader declares one.
    fn push_constant_type(&self) -> Option<u32> {
        let mut pointers = HashMap::new();
        let mut variable_type = None;
        for (op, o) in instructions(&self.words) {
            match op {
                OP_TYPE_POINTER if o.len() >= 3 && o[1] == STORAGE_PUSH_CONSTANT => {
                    pointers.insert(o[0], o[2]);
                }
                OP_VARIABLE if o.len() >= 3 && o[2] == STORAGE_PUSH_CONSTANT => variable_type = Some(o[0]),
                _ => {}
            }
        }
        pointers.get(&variable_type?).copied()
    }

    /// The push-constant block's name (`layout(push_constant) uniform Name { .. }`).
    pub fn push_constant_block(&self) -> Option<String> {
        let block = self.push_constant_type()?;
        instructions(&self.words)
            .find(|(op, o)| *op == OP_NAME && o.first() == Some(&block))
            .map(|(_, o)| string(&o[1..]))
    }

    /// The push-constant block's members in declaration order: (name, byte offset). Empty when
    /// the shader declares no push constants.
    pub fn push_constant_members(&self) -> Vec<(String, u32)> {
        let Some(block) = self.push_constant_type() else { return vec![] };
        let members = StructTypes::of(self).members(block).unwrap_or_default();
        members.into_iter().map(|m| (m.name, m.offset)).collect()
    }
}

/// The struct types of a module with their names, member names, member offsets and the array
/// strides of their member types: what [`Spirv::struct_layouts`] and
/// [`Spirv::push_constant_members`] read.
struct StructTypes {
    names: HashMap<u32, String>,
    member_names: HashMap<(u32, u32), String>,
    offsets: HashMap<(u32, u32), u32>,
    strides: HashMap<u32, u32>,
    /// (type id, member type ids) in declaration order.
    structs: Vec<(u32, Vec<u32>)>,
}

impl StructTypes {
    fn of(spirv: &Spirv) -> StructTypes {
        let mut t = StructTypes {
            names: HashMap::new(),
            member_names: HashMap::new(),
            offsets: HashMap::new(),
            strides: HashMap::new(),
            structs: vec![],
        };
        for (op, o) in instructions(&spirv.words) {
            match op {
                OP_NAME if o.len() >= 2 => {
                    t.names.insert(o[0], string(&o[1..]));
                }
                OP_MEMBER_NAME if o.len() >= 3 => {
                    t.member_names.insert((o[0], o[1]), string(&o[2..]));
                }
                OP_TYPE_STRUCT if !o.is_empty() => t.structs.push((o[0], o[1..].to_vec())),
                OP_DECORATE if o.len() >= 3 && o[1] == DECORATION_ARRAY_STRIDE => {
                    t.strides.insert(o[0], o[2]);
                }
                OP_MEMBER_DECORATE if o.len() >= 4 && o[2] == DECORATION_OFFSET => {
                    t.offsets.insert((o[0], o[1]), o[3]);
                }
                _ => {}
            }
        }
        t
    }

    /// The members of struct type `id` in declaration order, or None when it is not a struct
    /// with an Offset on every member (a function's local copy has none).
    fn members(&self, id: u32) -> Option<Vec<ReflectedMember>> {
        let (_, types) = self.structs.iter().find(|(s, _)| *s == id)?;
        let member = |(m, ty): (usize, &u32)| {
            Some(ReflectedMember {
                name: self.member_names.get(&(id, m as u32)).cloned().unwrap_or_default(),
                offset: *self.offsets.get(&(id, m as u32))?,
                array_stride: self.strides.get(ty).copied(),
            })
        };
        types.iter().enumerate().map(member).collect::<Option<Vec<_>>>().filter(|m| !m.is_empty())
    }
}

impl Spirv {
    /// The layouts glslang gave the struct types named `name` (a block's, or a struct's used in
    /// one), each with its members in declaration order. A struct type used in more than one
    /// layout appears once per layout; one without Offset decorations (a function's local copy)
    /// is left out.
    pub fn struct_layouts(&self, name: &str) -> Vec<Vec<ReflectedMember>> {
        let t = StructTypes::of(self);
        t.structs
            .iter()
            .filter(|(id, _)| t.names.get(id).map(String::as_str) == Some(name))
            .filter_map(|(id, _)| t.members(*id))
            .collect()
    }

    /// The descriptor bindings of set 0 in binding order. `Err` names what this reflection
    /// cannot describe (another set, a separate sampler, an array of descriptors).
    pub fn descriptor_bindings(&self) -> Result<Vec<ReflectedBinding>, String> {
        let mut names: HashMap<u32, String> = HashMap::new();
        let mut decorations: HashMap<u32, Vec<(u32, u32)>> = HashMap::new();
        let mut pointers: HashMap<u32, (u32, u32)> = HashMap::new();
        let mut images: HashMap<u32, u32> = HashMap::new();
        let mut sampled_images: HashMap<u32, u32> = HashMap::new();
        let mut arrays: HashMap<u32, u32> = HashMap::new();
        let mut structures: Vec<u32> = vec![];
        let mut variables = vec![];
        for (op, o) in instructions(&self.words) {
            match op {
                OP_NAME if o.len() >= 2 => {
                    names.insert(o[0], string(&o[1..]));
                }
                OP_DECORATE if o.len() >= 2 => {
                    decorations.entry(o[0]).or_default().push((o[1], o.get(2).copied().unwrap_or(0)));
                }
                OP_TYPE_POINTER if o.len() >= 3 => {
                    pointers.insert(o[0], (o[1], o[2]));
                }
                OP_TYPE_IMAGE if o.len() >= 7 => {
                    images.insert(o[0], o[6]);
                }
                OP_TYPE_SAMPLED_IMAGE if o.len() >= 2 => {
                    sampled_images.insert(o[0], o[1]);
                }
                OP_TYPE_ACCELERATION_STRUCTURE if !o.is_empty() => structures.push(o[0]),
                OP_TYPE_ARRAY if o.len() >= 2 => {
                    arrays.insert(o[0], o[1]);
                }
                OP_VARIABLE if o.len() >= 3 => variables.push((o[0], o[1], o[2])),
                _ => {}
            }
        }
        let decoration =
            |id: u32, d: u32| decorations.get(&id).and_then(|v| v.iter().find(|(k, _)| *k == d)).map(|x| x.1);
        let mut out = vec![];
        for (ptr_type, id, class) in variables {
            if ![STORAGE_UNIFORM_CONSTANT, STORAGE_UNIFORM, STORAGE_BUFFER].contains(&class) {
                continue;
            }
            let Some(binding) = decoration(id, DECORATION_BINDING) else { continue };
            let var_name = names.get(&id).cloned().unwrap_or_default();
            if decoration(id, DECORATION_DESCRIPTOR_SET).unwrap_or(0) != 0 {
                return Err(format!("`{var_name}` (binding {binding}) is not in descriptor set 0"));
            }
            let Some(&(_, pointee)) = pointers.get(&ptr_type) else { continue };
            if arrays.contains_key(&pointee) {
                return Err(format!("`{var_name}` (binding {binding}) is an array of descriptors"));
            }
            let kind = match class {
                STORAGE_BUFFER => BindingKind::StorageBuffer,
                STORAGE_UNIFORM if decoration(pointee, DECORATION_BUFFER_BLOCK).is_some() => BindingKind::StorageBuffer,
                STORAGE_UNIFORM if decoration(pointee, DECORATION_BLOCK).is_some() => BindingKind::UniformBuffer,
                _ if sampled_images.contains_key(&pointee) => BindingKind::SampledImage,
                _ if images.get(&pointee) == Some(&2) => BindingKind::StorageImage,
                _ if structures.contains(&pointee) => BindingKind::AccelerationStructure,
                _ => return Err(format!("`{var_name}` (binding {binding}): a descriptor kind vkcore does not use")),
            };
            let name = if var_name.is_empty() { names.get(&pointee).cloned().unwrap_or_default() } else { var_name };
            out.push(ReflectedBinding { binding, name, kind });
        }
        out.sort_by_key(|b| b.binding);
        Ok(out)
    }
}

#[cfg(test)]
mod tests {
    use super::{ReflectedBinding, ReflectedMember};
    use crate::pipeline::BindingKind;
    use crate::shader::ShaderCompiler;
    use std::path::PathBuf;

    /// A compiler over a fresh temp folder holding `files` (name, GLSL); the caller removes it.
    fn compiler_with(tag: &str, files: &[(&str, &str)]) -> (PathBuf, ShaderCompiler) {
        let root = std::env::temp_dir().join(format!("vkcore-reflect-{tag}-{}", std::process::id()));
        std::fs::create_dir_all(&root).unwrap();
        for (name, text) in files {
            std::fs::write(root.join(name), text).unwrap();
        }
        let c = ShaderCompiler::new(&root).unwrap();
        (root, c)
    }

    #[test]
    fn descriptor_bindings_by_name_and_kind() {
        let bindings = "#version 450\nlayout(local_size_x = 1) in;\n\
             layout(binding = 3) uniform sampler2D photon_position;\n\
             layout(std140, binding = 0) uniform FrameUniforms { vec4 eye; } frame;\n\
             layout(std430, binding = 1) buffer Photons { float x[]; };\n\
             layout(std430, binding = 2) readonly buffer Powers { float p[]; } powers;\n\
             layout(binding = 4, rgba32f) uniform writeonly image2D caustic_map;\n\
             void main() { x[0] = frame.eye.x + powers.p[0] + texture(photon_position, vec2(0)).x;\n\
             imageStore(caustic_map, ivec2(0), vec4(1)); }\n";
        let array = "#version 450\nlayout(local_size_x = 1) in;\nlayout(binding = 0) uniform sampler2D t[2];\n\
             layout(std430, binding = 1) buffer B { float x[]; };\nvoid main() { x[0] = texture(t[1], vec2(0)).x; }\n";
        let (root, c) = compiler_with("b", &[("b.comp", bindings), ("arr.comp", array)]);
        let s = c.compile("b.comp", &[]).unwrap();
        let want = [
            (0, "frame", BindingKind::UniformBuffer),
            (1, "Photons", BindingKind::StorageBuffer),
            (2, "powers", BindingKind::StorageBuffer),
            (3, "photon_position", BindingKind::SampledImage),
            (4, "caustic_map", BindingKind::StorageImage),
        ]
        .map(|(binding, name, kind)| ReflectedBinding { binding, name: name.into(), kind })
        .to_vec();
        assert_eq!(s.descriptor_bindings().unwrap(), want);
        let e = c.compile("arr.comp", &[]).unwrap().descriptor_bindings().unwrap_err();
        assert!(e.contains("`t`") && e.contains("array"), "{e}");
        std::fs::remove_dir_all(&root).unwrap();
    }

    #[test]
    fn struct_layouts_follow_std140_and_std430() {
        let shader = "#version 450\nlayout(local_size_x = 1) in;\n\
             struct S { vec3 a; float b; mat4 m[2]; vec2 c; };\n\
             layout(std140, binding = 0) uniform U { S s; float tail[3]; } u;\n\
             layout(std430, binding = 1) buffer B { S s; float tail[3]; } b;\n\
             void main() { b.s.c = u.s.m[1][0].xy + u.s.a.xy * u.s.b + vec2(u.tail[2]); b.tail[1] = 0.0; }\n";
        let (root, c) = compiler_with("s", &[("s.comp", shader)]);
        let s = c.compile("s.comp", &[]).unwrap();
        let member = |name: &str, offset, array_stride| ReflectedMember { name: name.into(), offset, array_stride };
        // std140 and std430 alike: vec3 at 0, the float packed after it at 12, mat4s of 64 bytes
        // from 16 (a 16-byte alignment), the vec2 after them at 144.
        let want_s =
            vec![member("a", 0, None), member("b", 12, None), member("m", 16, Some(64)), member("c", 144, None)];
        let layouts = s.struct_layouts("S");
        assert!(!layouts.is_empty() && layouts.iter().all(|l| *l == want_s), "{layouts:?}");
        // The blocks differ: a float array's stride is 16 under std140 and 4 under std430, and
        // the struct's size rounds up to 16 in both (152 -> 160).
        assert_eq!(s.struct_layouts("U"), vec![vec![member("s", 0, None), member("tail", 160, Some(16))]]);
        assert_eq!(s.struct_layouts("B"), vec![vec![member("s", 0, None), member("tail", 160, Some(4))]]);
        assert!(s.struct_layouts("Nothing").is_empty());
        std::fs::remove_dir_all(&root).unwrap();
    }

    #[test]
    fn push_constant_names_and_offsets() {
        let push = "#version 450\nlayout(local_size_x = 1) in;\n\
             layout(push_constant) uniform Things { vec4 colour; uint count; float scale; uvec2 pair; } things;\n\
             layout(std430, binding = 0) buffer B { float x[]; };\n\
             void main() { x[0] = things.colour.x + float(things.count) * things.scale + float(things.pair.y); }\n";
        let none = "#version 450\nlayout(local_size_x = 1) in;\nvoid main() {}\n";
        let (root, c) = compiler_with("p", &[("p.comp", push), ("none.comp", none)]);
        let s = c.compile("p.comp", &[]).unwrap();
        assert_eq!(s.push_constant_block().as_deref(), Some("Things"));
        let want: Vec<(String, u32)> =
            [("colour", 0), ("count", 16), ("scale", 20), ("pair", 24)].map(|(n, o)| (n.to_string(), o)).to_vec();
        assert_eq!(s.push_constant_members(), want);
        let none = c.compile("none.comp", &[]).unwrap();
        assert_eq!(none.push_constant_block(), None);
        assert!(none.push_constant_members().is_empty());
        std::fs::remove_dir_all(&root).unwrap();
    }
}
