//! Fuzz target `bench_config` (README.md): `cargo afl build --release --bin bench_config`, run by scripts/fuzz.sh.

fn main() {
    let root = causticlab_fuzz::fuzz_root();
    afl::fuzz!(|data: &[u8]| {
        causticlab_fuzz::run(causticlab_fuzz::check::Target::BenchConfig, &root, data);
    });
}
