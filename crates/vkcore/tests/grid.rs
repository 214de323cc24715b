//! `shaders_glsl/vkcore/dispatch_grid.glsl`, run on the device, gives the grid of its Rust twin
//! (`vkcore::dispatch_grid`) for every group count tried.

mod common;
use common::*;
use vkcore::*;

const COUNTS: [u32; 14] = [0, 1, 2, 63, 64, 65534, 65535, 65536, 65537, 131070, 131071, 262144, 1 << 22, (1 << 26) + 3];

#[test]
fn the_glsl_grid_equals_the_rust_grid() {
    let (ctx, _) = context();
    // The real include beside a test kernel, in a scratch shader root.
    let root = std::env::temp_dir().join(format!("vkcore-grid-{}", std::process::id()));
    std::fs::create_dir_all(root.join("vkcore")).unwrap();
    std::fs::copy(shader_root().join("vkcore/dispatch_grid.glsl"), root.join("vkcore/dispatch_grid.glsl")).unwrap();
    std::fs::write(
        root.join("grid.comp"),
        "#version 450\n#include \"vkcore/dispatch_grid.glsl\"\nlayout(local_size_x = 64) in;\n\
         layout(std430, binding = 0) readonly buffer In { uint counts[]; };\n\
         layout(std430, binding = 1) buffer Out { uvec2 grids[]; };\n\
         void main() { uint i = gl_GlobalInvocationID.x; if (i < counts.length()) grids[i] = dispatch_grid(counts[i]); }\n",
    )
    .unwrap();
    let shader = ShaderCompiler::new(&root).unwrap().compile("grid.comp", &[]).unwrap();
    let p = Pipeline::compute(&ctx, "grid", &shader).unwrap();
    let counts = ctx.buffer_with_data("counts", bytemuck::cast_slice(&COUNTS)).unwrap();
    let grids = Buffer::new(&ctx, "grids", COUNTS.len() as u64 * 8, Memory::Gpu).unwrap();
    let mut f = ctx.frame(FrameOptions::default()).unwrap();
    f.pass("grid")
        .bind(&p, [("In", Bind::BufferRead(&counts)), ("Out", Bind::Buffer(&grids))])
        .record(|cmd| {
            cmd.dispatch(1, 1, 1);
            Ok(())
        })
        .unwrap();
    f.submit().unwrap();
    let got: Vec<[u32; 2]> = ctx.read_buffer_as::<[u32; 2]>(&grids).unwrap();
    let want: Vec<[u32; 2]> = COUNTS.iter().map(|&g| dispatch_grid(g)).map(|(x, y)| [x, y]).collect();
    assert_eq!(got, want);
    drop((p, counts, grids));
    std::fs::remove_dir_all(&root).ok();
    assert_no_validation_messages(&ctx);
}
