//! Fuzz target `scene_values` (README.md): `cargo afl build --release --bin scene_values`, run by scripts/fuzz.sh.

fn main() {
    let root = causticlab_fuzz::fuzz_root();
    afl::fuzz!(|data: &[u8]| {
        causticlab_fuzz::run(causticlab_fuzz::check::Target::SceneValues, &root, data);
    });
}
