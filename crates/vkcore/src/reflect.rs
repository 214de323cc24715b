//! A little SPIR-V reflection: the push-constant block's name and its members' names and byte
//! offsets, read from the debug names (OpName, OpMemberName) and Offset decorations that
//! glslang writes. Enough to check a `#[repr(C)]` struct against its GLSL twin.

use crate::shader::Spirv;
use std::collections::HashMap;

const OP_NAME: u32 = 5;
const OP_MEMBER_NAME: u32 = 6;
const OP_TYPE_POINTER: u32 = 32;
const OP_VARIABLE: u32 = 59;
const OP_MEMBER_DECORATE: u32 = 72;
const STORAGE_PUSH_CONSTANT: u32 = 9;
const DECORATION_OFFSET: u32 = 35;

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
        let mut names = HashMap::new();
        let mut offsets = HashMap::new();
        for (op, o) in instructions(&self.words) {
            match op {
                OP_MEMBER_NAME if o.len() >= 3 && o[0] == block => {
                    names.insert(o[1], string(&o[2..]));
                }
                OP_MEMBER_DECORATE if o.len() >= 4 && o[0] == block && o[2] == DECORATION_OFFSET => {
                    offsets.insert(o[1], o[3]);
                }
                _ => {}
            }
        }
        let mut members: Vec<u32> = offsets.keys().copied().collect();
        members.sort();
        members.into_iter().map(|m| (names.get(&m).cloned().unwrap_or_default(), offsets[&m])).collect()
    }
}

#[cfg(test)]
mod tests {
    use crate::shader::ShaderCompiler;

    #[test]
    fn push_constant_names_and_offsets() {
        let root = std::env::temp_dir().join(format!("vkcore-reflect-{}", std::process::id()));
        std::fs::create_dir_all(&root).unwrap();
        std::fs::write(
            root.join("p.comp"),
            "#version 450\nlayout(local_size_x = 1) in;\n\
             layout(push_constant) uniform Things { vec4 colour; uint count; float scale; uvec2 pair; } things;\n\
             layout(std430, binding = 0) buffer B { float x[]; };\n\
             void main() { x[0] = things.colour.x + float(things.count) * things.scale + float(things.pair.y); }\n",
        )
        .unwrap();
        std::fs::write(root.join("none.comp"), "#version 450\nlayout(local_size_x = 1) in;\nvoid main() {}\n").unwrap();
        let c = ShaderCompiler::new(&root).unwrap();
        let s = c.compile("p.comp", &[]).unwrap();
        assert_eq!(s.push_constant_block().as_deref(), Some("Things"));
        let want: Vec<(String, u32)> =
            [("colour", 0), ("count", 16), ("scale", 20), ("pair", 24)].map(|(n, o)| (n.to_string(), o)).to_vec();
        assert_eq!(s.push_constant_members(), want);
        let none = c.compile("none.comp", &[]).unwrap();
        assert_eq!(none.push_constant_block(), None);
        assert!(none.push_constant_members().is_empty());
    }
}
