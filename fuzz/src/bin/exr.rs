//! Fuzz target `exr` (README.md): `cargo afl build --release --bin exr`, run by scripts/fuzz.sh.

fn main() {
    let root = causticlab_fuzz::fuzz_root();
    afl::fuzz!(|data: &[u8]| {
        causticlab_fuzz::run(causticlab_fuzz::check::Target::Exr, &root, data);
    });
}
