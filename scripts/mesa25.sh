#!/usr/bin/env bash
# Provides Mesa 25's lavapipe (Debian bookworm-backports' mesa-vulkan-drivers 25.0.7, with the
# newer libdrm it needs) beside the system's Mesa 22.3, without installing or replacing anything:
# the packages are downloaded with a private apt configuration (their own sources list and
# package lists, nothing under /etc/apt or /var/lib/apt is touched) and unpacked with `dpkg -x`
# into one folder. The default device, and every committed lavapipe table, stay on Mesa 22.3.
#
#   bash scripts/mesa25.sh            unpack if missing; print the folder
#   eval "$(bash scripts/mesa25.sh --env)"
#                                     this shell sees both lavapipes: Mesa 22.3 first (device 0,
#                                     the default), Mesa 25 second (`--device "Mesa 25"`)
#   eval "$(bash scripts/mesa25.sh --env-only)"
#                                     this shell sees Mesa 25's lavapipe alone
#   bash scripts/mesa25.sh --driver   what its driver line says, for --device: "Mesa 25.0.7"
#
# The version is 25.0.7-2~bpo12+1, the one the project was tested with; where backports has
# moved on, its newest mesa-vulkan-drivers is taken instead (and named by --driver). The folder
# is $CAUSTICLAB_MESA25_DIR, by default ~/.cache/causticlab/mesa-backports. Used by
# scripts/test.sh (the Mesa 25 step, scripts/mesa25_check.sh), docs/testing.md, and the
# ray-tracing work that needs the same driver. Exits non-zero, saying why, when the packages
# cannot be had (no network, not Debian 12, not amd64).
set -euo pipefail

version=25.0.7-2~bpo12+1
dir=${CAUSTICLAB_MESA25_DIR:-${XDG_CACHE_HOME:-$HOME/.cache}/causticlab/mesa-backports}
mode=${1:-}
case "$mode" in "" | --env | --env-only | --driver) ;; *)
    echo "usage: $0 [--env | --env-only | --driver]" >&2
    exit 2
    ;;
esac

unpacked=$dir/root/usr/lib/x86_64-linux-gnu
# The newer libdrm Mesa 25 needs, alone in a folder for LD_LIBRARY_PATH (the unpacked folder
# also holds Mesa 25's layers and other drivers, which the system's layer manifests would pick).
lib=$dir/lib
icd=$dir/lvp_icd.mesa25.json
system_icd=/usr/share/vulkan/icd.d/lvp_icd.x86_64.json

if [ ! -f "$icd" ] || [ ! -f "$unpacked/libvulkan_lvp.so" ] || [ ! -e "$lib/libdrm.so.2" ] || [ ! -f "$dir/version" ]; then
    if [ "$(dpkg --print-architecture 2>/dev/null)" != amd64 ]; then
        echo "mesa25: only amd64 is provided (Debian bookworm-backports' amd64 packages)" >&2
        exit 1
    fi
    case "$(cat /etc/debian_version 2>/dev/null)" in 12.*) ;; *)
        echo "mesa25: needs Debian 12 (bookworm-backports' packages link its libraries)" >&2
        exit 1
        ;;
    esac
    apt_dir=$dir/apt
    rm -rf "$dir/root" "$dir/lib" "$apt_dir"
    mkdir -p "$apt_dir/lists/partial" "$apt_dir/cache/archives/partial" "$apt_dir/debs"
    echo "deb http://deb.debian.org/debian bookworm-backports main" >"$apt_dir/sources.list"
    apt=(-o "Dir::Etc::SourceList=$apt_dir/sources.list" -o Dir::Etc::SourceParts=/dev/null
        -o "Dir::State::Lists=$apt_dir/lists" -o "Dir::Cache=$apt_dir/cache" -o APT::Sandbox::User=root)
    echo "mesa25: downloading mesa-vulkan-drivers $version (bookworm-backports) into $dir" >&2
    apt-get "${apt[@]}" update >"$apt_dir/update.log" 2>&1 ||
        { echo "mesa25: apt-get update of bookworm-backports failed (see $apt_dir/update.log)" >&2; exit 1; }
    get() { (cd "$apt_dir/debs" && apt-get "${apt[@]}" download "$@") >>"$apt_dir/download.log" 2>&1; }
    get "mesa-vulkan-drivers=$version" || get mesa-vulkan-drivers/bookworm-backports ||
        { echo "mesa25: apt-get download of mesa-vulkan-drivers failed (see $apt_dir/download.log)" >&2; exit 1; }
    get libdrm2/bookworm-backports libdrm-amdgpu1/bookworm-backports ||
        { echo "mesa25: apt-get download of libdrm failed (see $apt_dir/download.log)" >&2; exit 1; }
    for deb in "$apt_dir"/debs/*.deb; do
        dpkg -x "$deb" "$dir/root"
    done
    dpkg-deb -f "$apt_dir"/debs/mesa-vulkan-drivers_*.deb Version >"$dir/version"
    mkdir -p "$lib"
    ln -s "$unpacked/libdrm.so.2" "$unpacked/libdrm_amdgpu.so.1" "$lib/"
    # The package's manifest names the library by file name alone (the system's search path);
    # this one names the unpacked copy.
    sed "s#\"library_path\": *\"[^\"]*\"#\"library_path\": \"$unpacked/libvulkan_lvp.so\"#" \
        "$dir/root/usr/share/vulkan/icd.d/lvp_icd.json" >"$icd"
    rm -rf "$apt_dir/cache" "$apt_dir/lists"
fi

case "$mode" in
"") echo "$dir" ;;
--driver)
    # 25.0.7-2~bpo12+1 -> "Mesa 25.0.7", as the driver line starts.
    echo "Mesa $(sed 's/-.*//' "$dir/version")"
    ;;
--env)
    [ -f "$system_icd" ] || { echo "mesa25: the system's lavapipe ($system_icd) is missing: run scripts/setup.sh" >&2; exit 1; }
    # Debian 12's loader (1.3.239) enumerates the files of VK_DRIVER_FILES last to first: listed
    # so, the system's lavapipe stays device 0 and the default (scripts/mesa25_check.sh checks).
    echo "export VK_DRIVER_FILES='$icd:$system_icd'"
    echo "export LD_LIBRARY_PATH='$lib'\${LD_LIBRARY_PATH:+:\$LD_LIBRARY_PATH}"
    ;;
--env-only)
    echo "export VK_DRIVER_FILES='$icd'"
    echo "export LD_LIBRARY_PATH='$lib'\${LD_LIBRARY_PATH:+:\$LD_LIBRARY_PATH}"
    ;;
esac
