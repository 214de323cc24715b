//! shaderc-sys links Debian's `libshaderc_combined.a`, which on Debian does not bundle
//! glslang and SPIRV-Tools: link their static libraries (from `glslang-dev`, `spirv-tools`) here.
fn main() {
    let dir = std::env::var("SHADERC_LIB_DIR").unwrap_or_else(|_| "/usr/lib/x86_64-linux-gnu".into());
    println!("cargo:rustc-link-search=native={dir}");
    for lib in [
        "glslang",
        "MachineIndependent",
        "OSDependent",
        "GenericCodeGen",
        "OGLCompiler",
        "SPIRV",
        "SPIRV-Tools-opt",
        "SPIRV-Tools",
    ] {
        println!("cargo:rustc-link-lib=static={lib}");
    }
    println!("cargo:rerun-if-env-changed=SHADERC_LIB_DIR");
}
