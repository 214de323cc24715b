#!/usr/bin/env bash
# Validates the Kubernetes manifests of scripts/cluster/submit.sh --k8s offline against the
# Job schema of Kubernetes $K8S_VERSION (default 1.31.0), with `kubernetes-validate` from PyPI
# installed into a throwaway virtual environment (scripts/test.sh runs it; no cluster runs the
# manifests here). Checks too that the validator fails on a manifest with a wrong field, so that
# a pass means something.
#
#   bash scripts/cluster/k8s_check.sh
#
# Needs python3 with venv (as root it installs Debian's python3-venv where venv is missing) and
# PyPI; without them it says so and exits 1.
set -euo pipefail
cd "$(dirname "$0")/../.."
version=${K8S_VERSION:-1.31.0}
fail() { echo "k8s_check: FAILED: $*" >&2; exit 1; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

if ! python3 -m venv "$tmp/venv" >/dev/null 2>&1; then
    # Debian's python3 has venv in a package of its own.
    [ "$(id -u)" -eq 0 ] || fail "python3 -m venv failed (apt-get install python3-venv)"
    DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends python3-venv >/dev/null \
        || fail "python3 -m venv failed and python3-venv could not be installed"
    rm -rf "$tmp/venv"
    /usr/bin/python3 -m venv "$tmp/venv" >/dev/null || fail "python3 -m venv failed after installing python3-venv"
fi
"$tmp/venv/bin/pip" install -q kubernetes-validate >"$tmp/pip.log" 2>&1 || { tail -n 5 "$tmp/pip.log"; fail "pip could not install kubernetes-validate"; }
kv=("$tmp/venv/bin/kubernetes-validate" --kubernetes-version "$version" --strict)

# A stand-in pack: the manifests name no file in it.
mkdir -p "$tmp/pack"
: >"$tmp/pack/causticlab.xz"
: >"$tmp/pack/tree.tar.xz"
bash scripts/cluster/submit.sh --k8s --image registry.example/causticlab:1 --pvc causticlab-shared \
    --shared "$tmp/shared" --pack "$tmp/pack" --name k8s-check --target 'H100=NVIDIA-H100-80GB-HBM3' \
    --target A100 --throttle 2 --shards 4 --quick wyman2008_table1 wyman2008_fig7
mapfile -t manifests < <(find "$tmp/shared/runs" -name 'k8s-*.yaml' | sort)
[ "${#manifests[@]}" -eq 4 ] || fail "${#manifests[@]} manifests, not 4 (an array and a merge per target)"
for m in "${manifests[@]}"; do
    "${kv[@]}" "$m" || fail "${m#"$tmp/"} is not a valid Job of Kubernetes $version"
done
a=$tmp/shared/runs/k8s-check.1/k8s-array.yaml
grep -q '^  completionMode: Indexed$' "$a" || fail "the array is not an Indexed Job"
grep -q '^  completions: 8$' "$a" || fail "the array does not have 8 completions (2 configs of 4 shards)"
grep -q 'nvidia.com/gpu.product: "NVIDIA-H100-80GB-HBM3"' "$a" || fail "the first target's constraint is not its node selector"
grep -q 'value: graphics,compute,utility' "$a" || fail "the array does not ask for the driver's graphics capability"
! grep -q 'nodeSelector' "$tmp/shared/runs/k8s-check.2/k8s-array.yaml" || fail "the second target (no constraint) has a node selector"

# The validator must be able to fail: a misspelt field, and a completion count that is a string.
sed 's/completionMode: Indexed/completionMod: Indexed/' "$a" >"$tmp/bad1.yaml"
sed 's/completions: 8/completions: "eight"/' "$a" >"$tmp/bad2.yaml"
for bad in bad1 bad2; do
    if "${kv[@]}" "$tmp/$bad.yaml" >/dev/null 2>&1; then fail "kubernetes-validate accepted $bad.yaml"; fi
done
echo "k8s_check: ok: ${#manifests[@]} manifests valid against Kubernetes $version's Job schema; 2 broken ones refused"
