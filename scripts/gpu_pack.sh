#!/usr/bin/env bash
# Packs what a GPU run needs into .gpu/ (ignored by git), for a machine with no Rust toolchain, no
# internet and no Vulkan loader: the stripped release binary, the Vulkan loader as Debian packages
# (amd64), the font the plots are drawn with, the shared models the suite's configs need
# (xz-compressed), and a manifest naming the commit the binary was built from (the .git folder
# may not travel, so the tables take the commit from the pack). The step-by-step is in
# docs/bench.md, "A GPU run".
#
#   bash scripts/gpu_pack.sh                     # build the release binary, then pack
#   bash scripts/gpu_pack.sh --binary PATH       # pack this binary instead of building one
#   bash scripts/gpu_pack.sh --dry-run --binary target/debug/causticlab   # CI: size check only
#   bash scripts/gpu_pack.sh --binary B --out DIR --no-loader   # a pack for a lavapipe dry run
#   bash scripts/gpu_pack.sh --binary B --out DIR --cluster     # a pack for scripts/cluster/ (below)
#
# It needs this machine's apt sources and network (it downloads the loader's .debs), and the
# models in ../shared/models (--models DIR, or $CAUSTICLAB_MODELS_DIR); the font is
# DejaVu Sans from fonts-dejavu-core (or $CAUSTICLAB_FONT).
# It prints the pack's size and what would travel in all (the working tree that git does not
# ignore, plus the pack), and fails if that exceeds the 64 MiB a device call may carry.
# --dry-run packs into a temporary folder and leaves .gpu/ alone; --no-loader leaves the Vulkan
# loader out (for a machine that has one: the suite then uses it). --cluster adds what the
# working tree gives a device call (tree.tar.xz: bench_configs/, scenes/, shaders_glsl/, as
# tracked) for the nodes of a cluster, which get the pack alone (scripts/cluster/, docs/bench.md
# "On a cluster"); it leaves out the 64 MiB check, which is a device call's.
set -euo pipefail
cd "$(dirname "$0")/.."

limit_mib=64
binary=""
dry_run=0
loader=1
cluster=0
pack=.gpu
models_dir=${CAUSTICLAB_MODELS_DIR:-../shared/models}
while [ $# -gt 0 ]; do
    case "$1" in
        --binary|--models|--out) [ $# -ge 2 ] || { echo "gpu_pack: $1 needs a value (see --help)" >&2; exit 2; } ;;&
        --binary) binary=$2; shift 2 ;;
        --dry-run) dry_run=1; shift ;;
        --out) pack=$2; shift 2 ;;
        --no-loader) loader=0; shift ;;
        --cluster) cluster=1; shift ;;
        --models) models_dir=$2; shift 2 ;;
        -h|--help) awk 'NR > 1 && /^#/ { sub(/^# ?/, ""); print; next } NR > 1 { exit }' "$0"; exit 0 ;;
        *) echo "gpu_pack: unknown argument '$1' (see --help)" >&2; exit 2 ;;
    esac
done

# The configs scripts/gpu_suite.sh runs (its priority list is the one source of this list).
mapfile -t configs < <(bash scripts/gpu_suite.sh --list-configs)

if [ -z "$binary" ]; then
    cargo build --release -p causticlab
    binary=target/release/causticlab
fi
[ -x "$binary" ] || { echo "gpu_pack: no executable binary at $binary" >&2; exit 1; }

work_bin=$(mktemp)
if [ "$dry_run" -eq 1 ]; then
    pack=$(mktemp -d)
    trap 'rm -rf "$pack" "$work_bin"' EXIT
else
    if [ -e "$pack" ] && [ ! -f "$pack/MANIFEST" ] && [ -n "$(ls -A "$pack" 2>/dev/null)" ]; then
        echo "gpu_pack: $pack exists and is not a pack (no MANIFEST): refusing to replace it" >&2
        exit 1
    fi
    rm -rf "$pack"
    mkdir -p "$pack"
fi

# 1. The binary, stripped and xz-compressed (shaderc is linked statically; the rest is glibc and
#    libstdc++, which the GPU machine has).
strip -o "$work_bin" "$binary"
binary_bytes=$(stat -c %s "$work_bin")
binary_sha=$(sha256sum "$work_bin" | cut -c1-16)
binary_version=$("$work_bin" --version 2>/dev/null || echo '?')
xz -T0 -6 -c "$work_bin" >"$pack/causticlab.xz"
rm -f "$work_bin"

# 2. The Vulkan loader and the GL vendor libraries the NVIDIA driver's ICD loads, for amd64, from
#    this machine's apt sources (lists kept in a private folder: the system's are untouched).
if [ "$dry_run" -eq 0 ] && [ "$loader" -eq 1 ]; then
    lists=$(mktemp -d)
    mkdir -p "$lists/partial" "$pack/debs"
    apt=(-oAPT::Architecture=amd64 -oAPT::Architectures=amd64 "-oDir::State::Lists=$lists")
    apt-get "${apt[@]}" update >/dev/null
    (cd "$pack/debs" && apt-get "${apt[@]}" download libvulkan1 libglvnd0 libgl1 libglx0 libegl1 libopengl0 libgles2 2>/dev/null)
    rm -rf "$lists"
elif [ "$dry_run" -eq 1 ]; then
    mkdir -p "$pack/debs"   # the dry run counts the loader as its usual ~0.4 MB
    head -c 400000 /dev/zero >"$pack/debs/placeholder"
fi

# 3. The plots' font (crates/bench/src/font.rs): `bench` checks for it before its first cell, so
#    the suite sets CAUSTICLAB_FONT to it; the suite writes parts only, and gpu_unpack.sh draws
#    the plots at home.
font=${CAUSTICLAB_FONT:-/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf}
[ -f "$font" ] || { echo "gpu_pack: no font at $font (apt-get install fonts-dejavu-core)" >&2; exit 1; }
cp "$font" "$pack/DejaVuSans.ttf"

# 4. The models named by the scenes of the suite's configs (`file = "x.obj"`), compressed.
models=()
for c in "${configs[@]}"; do
    for scene in $(sed -n '/^scenes *=/,/]/p' "bench_configs/$c.toml" | grep -o '"[^"]*\.toml"' | tr -d '"'); do
        for m in $(grep -o '^file *= *"[^"]*\.obj"' "bench_configs/$scene" | grep -o '"[^"]*"' | tr -d '"'); do
            models+=("$m")
        done
    done
done
mapfile -t models < <(printf '%s\n' "${models[@]}" | sort -u)
missing=()
present=()
for m in "${models[@]}"; do
    if [ -f "$models_dir/$m" ]; then present+=("$m"); else missing+=("$m"); fi
done
if [ "${#missing[@]}" -gt 0 ]; then
    echo "gpu_pack: models missing from $models_dir: ${missing[*]} (their cells would fail there)" >&2
    exit 1
fi
tar -C "$models_dir" -cJf "$pack/models.tar.xz" "${present[@]}"

# 4b. For a cluster: the tracked files a run reads from the working tree.
if [ "$cluster" -eq 1 ]; then
    git ls-files -z -- bench_configs scenes shaders_glsl | tar --null -T - -cJf "$pack/tree.tar.xz"
fi

# 5. The manifest: the commit the binary was built from (dirty if tracked code differs).
source scripts/commit.sh
commit=$(code_commit 2>/dev/null) || commit=unknown
echo "$commit" >"$pack/COMMIT"
{
    echo "causticlab GPU pack"
    echo "commit: $commit"
    echo "packed: $(date -u +%Y-%m-%dT%H:%M:%SZ) on $(uname -srm)"
    echo "binary: causticlab.xz, $binary_bytes bytes unpacked, sha256 $binary_sha ($binary_version)"
    echo "configs: ${configs[*]}"
    echo "models: ${present[*]}"
    echo "files:"
    (cd "$pack" && find . -type f ! -name MANIFEST | sort | while read -r f; do
        printf '  %-40s %10d bytes\n' "${f#./}" "$(stat -c %s "$f")"
    done)
} >"$pack/MANIFEST"

pack_bytes=$(du -sb "$pack" | cut -f1)
mib() { awk -v b="$1" 'BEGIN {printf "%.1f MiB", b / 1048576}'; }
if [ "$cluster" -eq 1 ]; then
    echo "gpu_pack: wrote $pack/ for a cluster ($(mib "$pack_bytes"), commit $commit)"
    exit 0
fi
# 6. What would travel to a lent machine: the files git does not ignore (tracked and
# untracked) that are there (a tracked file deleted in the work tree does not travel), plus the
# pack.
present() { while IFS= read -r -d '' f; do if [ -f "$f" ]; then printf '%s\0' "$f"; fi; done; }
# "bytes path" of every tracked file under results/ that is there.
results_sizes() { git ls-files -z -- results | present | xargs -0 -r stat -c '%s %n'; }
tree_bytes=$(git ls-files -z --cached --others --exclude-standard | present | xargs -0 -r stat -c %s | awk '{s+=$1} END {print s+0}')
total=$((tree_bytes + pack_bytes))
echo "gpu_pack: pack $(mib "$pack_bytes") (binary $(mib "$(stat -c %s "$pack/causticlab.xz")") xz, models $(mib "$(stat -c %s "$pack/models.tar.xz")")); working tree $(mib "$tree_bytes"); transfer $(mib "$total") of $limit_mib MiB"
if [ "$total" -gt $((limit_mib * 1048576)) ]; then
    echo "gpu_pack: the transfer would exceed $limit_mib MiB; the largest folders under results/:" >&2
    results_sizes | awk '{ split($2, p, "/"); s[p[1] "/" p[2]] += $1 }
        END { for (d in s) printf "%10.1f MiB  %s\n", s[d] / 1048576, d }' | sort -rn | head -n 5 >&2
    echo "gpu_pack: a GPU folder that a newer run of the same configs has replaced can go (git keeps it; docs/bench.md, A GPU run)" >&2
    exit 1
fi
# Room for the next GPU run: its folder will be about the size of the largest GPU folder here
# (a device folder, one with bench tables, that is not lavapipe's). Where that would not fit, say
# so now, while the run's results can still land (they are committed after the run; the next
# pack carries them).
gpu_folder=$(results_sizes \
    | awk '{ split($2, p, "/"); if (p[3] == "" || p[2] ~ /^llvmpipe/) next; s[p[2]] += $1
             if (p[4] == "" && p[3] ~ /\.json(\.gz)?$/) tables[p[2]] = 1 }
        END { for (d in tables) if (s[d] > most) { most = s[d]; name = d } if (name != "") print most, name }')
if [ -n "$gpu_folder" ] && [ $((total + ${gpu_folder%% *})) -gt $((limit_mib * 1048576)) ]; then
    echo "gpu_pack: warning: one more GPU folder the size of results/${gpu_folder#* } ($(mib "${gpu_folder%% *}")) would not fit in $limit_mib MiB: remove a GPU folder a newer run has replaced before the next GPU run's results are committed (docs/bench.md, A GPU run)" >&2
fi
if [ "$dry_run" -eq 0 ]; then
    echo "gpu_pack: wrote $pack/ (commit $commit); on the GPU machine: bash scripts/gpu_suite.sh BUDGET_SECONDS \$OUT (docs/bench.md)"
fi
