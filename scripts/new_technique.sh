#!/usr/bin/env bash
# Stamps a new caustic technique (issue 50, item 5; docs/adding_a_technique.md walks through
# what follows):
#
#   bash scripts/new_technique.sh NAME PAPER
#
# NAME is the technique as `--technique` takes it (lower case and hyphens: `my-splat`); PAPER
# is its paper's folder under crates/caustics/src/techniques/: an existing one (`wyman2008`)
# or a new one (`smith2024`, made with its `mod.rs` and `settings.rs`, and placed in the module
# layers beside the other papers). It writes
#   - crates/caustics/src/techniques/PAPER/NAME.rs: the technique's own stage variant, a
#     struct with `new` (its pipeline: it compiles the shader below) and `record` (its
#     passes, empty), and a test that its shader compiles;
#   - shaders_glsl/PAPER/NAME.comp: its shader, a compute pass that does nothing yet;
#   - a variant of `Technique` (crates/caustics/src/techniques/technique.rs);
#   - its row in the registry of variants (crates/caustics/src/techniques/variants.toml), with
#     the accuracy it must state against the exact reference (the conformance suite holds it);
#   - crates/caustics/tests/PAPER_NAME.rs: a test that its frame records a pass of its own and
#     lights the receiver, which fails until it does.
# A new PAPER's registry key is added to techniques/variants.rs's PAPERS.
# (NAME in file names with underscores.) Then `cargo build` fails at every exhaustive `match`
# over `Technique` that has no arm for it, and once it builds, the tests say what is left
# (docs/adding_a_technique.md). Nothing is written when NAME or PAPER is not a valid name or
# NAME is a technique already.
set -euo pipefail
cd "$(dirname "$0")/.."

usage() {
    echo "usage: bash scripts/new_technique.sh NAME PAPER   (e.g. my-splat wyman2008)" >&2
    exit 2
}
[ $# -eq 2 ] || usage
name="$1"
paper="$2"
if ! [[ "$name" =~ ^[a-z][a-z0-9]*(-[a-z0-9]+)*$ ]]; then
    echo "new_technique: NAME \`$name\`: lower-case letters, digits and single hyphens, starting with a letter" >&2
    exit 2
fi
if ! [[ "$paper" =~ ^[a-z][a-z0-9_]*$ ]] || [ "$paper" = shared ] || [ "$paper" = stages ]; then
    echo "new_technique: PAPER \`$paper\`: a folder name (lower case, digits, underscores), not shared or stages" >&2
    exit 2
fi

src=crates/caustics/src/techniques
# Rust's keywords cannot name a module.
keywords=" as async await box break const continue crate dyn else enum extern false final fn for gen if impl in \
let loop macro match mod move mut override priv pub ref return self static struct super trait true try type \
typeof unsafe unsized use virtual where while yield "
for word in "$paper" "${name//-/_}"; do
    if [[ "$keywords" == *" $word "* ]]; then
        echo "new_technique: \`$word\` is a Rust keyword and cannot name a module" >&2
        exit 2
    fi
done
if [ -e "$src/$paper.rs" ]; then
    echo "new_technique: PAPER \`$paper\`: $src/$paper.rs is a module of the registry, not a paper's folder" >&2
    exit 2
fi
technique_rs="$src/technique.rs"
snake="${name//-/_}"
camel="$(echo "$name" | awk -F- '{ for (i = 1; i <= NF; i++) printf "%s%s", toupper(substr($i, 1, 1)), substr($i, 2) }')"
if grep -q "= \"$name\",\$" "$technique_rs" || grep -qE "^ +$camel = " "$technique_rs"; then
    echo "new_technique: \`$name\` is a technique already ($technique_rs)" >&2
    exit 2
fi
if grep -q "^name = \"$name\"\$" "$src/variants.toml"; then
    echo "new_technique: \`$name\` is a row of the registry already ($src/variants.toml)" >&2
    exit 2
fi
for f in "$src/$paper/$snake.rs" "shaders_glsl/$paper/$snake.comp" "crates/caustics/tests/${paper}_$snake.rs"; do
    if [ -e "$f" ]; then
        echo "new_technique: $f exists already" >&2
        exit 2
    fi
done

# The registry's paper key (the claims check's) of the paper's folder.
case "$paper" in
    trendall_stewart2000) key=trendall2000 ;;
    shah2007) key=shah ;;
    photon_trace) key=causticlab ;;
    *) key="$paper" ;;
esac

written=()
formatted=("$technique_rs" "$src/$paper/$snake.rs")

# Adds "$2" to the `pub const PAPERS` list of file $1 (on one line or one item per line).
add_to_papers() {
    awk -v x="$2" '
        /^pub const PAPERS/ { inside = 1 }
        inside && /\];/ {
            if ($0 ~ /^ *\];/) { print "    \"" x "\","; } else { sub(/\];/, ", \"" x "\"];") }
            inside = 0
        }
        { print }
    ' "$1" >"$1.new"
    mv "$1.new" "$1"
}

# A new paper's folder: its module, its settings (what the technique enum reads) and its place
# in the module layers.
if [ ! -d "$src/$paper" ]; then
    mkdir -p "$src/$paper"
    cat >"$src/$paper/mod.rs" <<EOF
//! TODO: the paper (authors, title, venue and year) and what of it this folder implements.

pub mod settings;
EOF
    cat >"$src/$paper/settings.rs" <<EOF
//! What $paper declares to the technique enum (a leaf module: it imports no passes).

use crate::dump::Dump;

/// The technique's source, as tables and \`--help\` cite it.
pub const PAPER: &str = "TODO: authors, title, venue year";

/// The buffers its stages own (\`--dump\`), each declared once in the module that writes it.
pub static DUMPS: &[&Dump] = &[];
EOF
    # In order among the module lines, as rustfmt keeps them.
    awk -v p="$paper" '
        !done && /^(pub )?mod [a-z0-9_]+;$/ {
            m = $NF; m = substr(m, 1, length(m) - 1)
            if (m > p) { print "pub mod " p ";"; done = 1 }
        }
        !done && seen && !/^(pub )?mod / { print "pub mod " p ";"; done = 1 }
        /^(pub )?mod / { seen = 1 }
        { print }
    ' "$src/mod.rs" >"$src/mod.rs.new"
    mv "$src/mod.rs.new" "$src/mod.rs"
    layers=crates/caustics/tests/module_layers
    awk -v p="$paper" '{ print } /^        "techniques::photon_trace",$/ { print "        \"techniques::" p "\"," }' \
        "$layers/main.rs" >"$layers/main.rs.new"
    mv "$layers/main.rs.new" "$layers/main.rs"
    add_to_papers "$layers/layers.rs" "$paper"
    # A new paper is a key the registry's rows may name (the claims check has its own list,
    # crates/bench/src/claims/page.rs, which needs the paper's text in ../shared/papers).
    add_to_papers "$src/variants.rs" "$key"
    written+=("$src/$paper/mod.rs" "$src/$paper/settings.rs" "$src/mod.rs" "$layers/main.rs" "$layers/layers.rs")
    written+=("$src/variants.rs")
    formatted+=("$layers/layers.rs" "$src/variants.rs" "$src/$paper/mod.rs")
fi

# The technique's own stage variant and its shader.
cat >"$src/$paper/$snake.rs" <<EOF
//! \`$name\`: TODO: what it does, citing the paper's section or equation.
//!
//! Make it an arm of the stage it replaces (\`techniques::stages\`: a photon \`Source\`, a
//! \`Selection\` or a \`Deposit\`), chosen in \`CausticPipeline::new\` for \`Technique::$camel\`.

use crate::gpu::Stage;
use anyhow::Result;
use vkcore::{Context, Frame, Pipeline, ShaderCompiler};

/// Its pipeline, made once per renderer.
pub struct $camel {
    pipeline: Pipeline,
}

impl $camel {
    pub fn new(ctx: &Context, sh: &ShaderCompiler) -> Result<$camel> {
        let shader = sh.compile("$paper/$snake.comp", &[])?;
        Ok($camel { pipeline: Pipeline::compute(ctx, "$paper.$snake", &shader)? })
    }

    /// Records its passes for light \`light\`. TODO: bind what it reads and writes and dispatch;
    /// give its pass a \`Stage\` of its own named \`$snake\` (\`gpu/pass_name.rs\`).
    pub fn record(&self, f: &mut Frame, light: u32) -> Result<()> {
        let _ = (&self.pipeline, f, light, Stage::Splat);
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    #[test]
    fn its_shader_compiles() {
        let sh = vkcore::ShaderCompiler::new(&crate::render::shader_root()).expect("shaderc");
        sh.compile("$paper/$snake.comp", &[]).expect("$paper/$snake.comp");
    }
}
EOF
echo "pub mod $snake;" >>"$src/$paper/mod.rs"
mkdir -p "shaders_glsl/$paper"
cat >"shaders_glsl/$paper/$snake.comp" <<EOF
#version 450
// \`$name\` ($paper): TODO: what this pass computes, citing the paper's section or equation.

layout(local_size_x = 64) in;

void main() {
}
EOF
written+=("$src/$paper/$snake.rs" "$src/$paper/mod.rs" "shaders_glsl/$paper/$snake.comp")

# Its variant of the closed set of techniques: the last before the enum's end.
awk -v c="$camel" -v n="$name" '
    /^    pub enum Technique \{$/ { inside = 1 }
    inside && /^    \}$/ {
        print "        /// TODO: one line on what it is (its paper and section)."
        print "        " c " = \"" n "\","
        inside = 0
    }
    { print }
' "$technique_rs" >"$technique_rs.new"
mv "$technique_rs.new" "$technique_rs"
written+=("$technique_rs")

# Its row in the registry of variants.
cat >>"$src/variants.toml" <<EOF

# --- $name (stamped by scripts/new_technique.sh: fill in the label, section and stated
#     accuracy; the conformance suite holds the technique to \`stated\`) ---

[[variant]]
name = "$name"
label = "$name"
paper = "$key"
section = "TODO"
default = true
settings = { technique = "$name" }
stated = { power = 0.02, rel_rmse = 0.25 }
EOF
written+=("$src/variants.toml")

# A test that fails until the technique records a pass of its own and lights the receiver.
cat >"crates/caustics/tests/${paper}_$snake.rs" <<EOF
//! \`$name\` ($paper), stamped by scripts/new_technique.sh: it fails until the technique's frame
//! records a pass of its own (a \`Stage\` named \`$snake\`, \`gpu/pass_name.rs\`: until then the
//! stages' default arms render it as \`shah\`) and puts a caustic on the receiver. Its accuracy
//! against the exact photon reference is the conformance suite's (its row's \`stated\` in the
//! registry of variants).

use caustics::render::{FrameStep, Renderer, RendererOptions};

mod common;
use common::{context, shipped};

#[test]
fn ${snake}_records_its_own_pass_and_lights_the_receiver() {
    let mut scene = shipped("sphere_on_plane.toml");
    scene.caustics.technique = "$name".parse().expect("a technique");
    scene.caustics.photons = 64;
    scene.caustics.caustic_map_resolution = 64;
    let (ctx, sh) = context();
    let mut r = Renderer::new(&ctx, &sh, &scene, &RendererOptions::default()).expect("renderer");
    let report = r.frame(FrameStep::default()).expect("frame");
    let passes: Vec<&str> = report.passes.iter().map(|p| p.name.as_str()).collect();
    assert!(passes.iter().any(|p| p.starts_with("$snake")), "no pass of \`$name\`'s own: {passes:?}");
    let receiver = r.receiver_map().expect("read back").expect("the scene has a receiver map");
    let caustic = receiver.layers.iter().find(|l| l.name.as_deref() == Some("caustic")).expect("caustic layer");
    let power: f64 = caustic.data.iter().map(|&x| x as f64).sum();
    assert!(power > 0.0, "\`$name\` put no caustic on the receiver");
}
EOF
written+=("crates/caustics/tests/${paper}_$snake.rs")

# rustfmt's layout for the lists it lengthened and the files it wrote (a new paper's mod.rs
# declares only the new files, so nothing else is formatted); where rustfmt is installed.
if command -v rustfmt >/dev/null; then
    rustfmt --edition 2021 "${formatted[@]}" || echo "new_technique: rustfmt could not format the stamped files (see above)" >&2
fi

echo "new_technique: \`$name\` (Technique::$camel) in $src/$paper/. Written:"
printf '  %s\n' "${written[@]}" | sort -u
echo "Next: cargo build -p caustics; every error is a match over Technique that needs the arm of"
echo "Technique::$camel. Then cargo test -p caustics --test ${paper}_$snake --test conformance."
