pub fn compile_test() -> usize {
    let c = shaderc::Compiler::new().unwrap();
    let a = c.compile_into_spirv("#version 450\nvoid main(){}", shaderc::ShaderKind::Compute, "t.comp", "main", None).unwrap();
    let _ = ash::vk::Format::R32_SFLOAT;
    a.as_binary().len()
}
#[cfg(test)]
mod t { #[test] fn c() { assert!(super::compile_test() > 0); } }
